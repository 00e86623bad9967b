// One surfaceless EGL display and OpenGL 4.3 core context (Mesa llvmpipe where there is no
// GPU) with the entry points the shader tests, the GPU bench and `scatterlut report` use, and
// program building. No test framework here: tests/gpu_harness.hpp (the shader tests),
// bench/gpu_bench.hpp and host/src/report_gpu.cpp include it. Everything is inside
// SLUT_HAVE_EGL (1 where the build found EGL/egl.h and GL/glcorearb.h).
//
// The EGL library itself: linked (the tests and the bench link libEGL), or, with
// SLUT_EGL_DLOPEN=1, loaded at run time with dlopen("libEGL.so.1") (the `scatterlut`
// executable: it starts and runs without libEGL, and the report says why it measured no GPU).
// The OpenGL entry points come from eglGetProcAddress either way.
#pragma once

#ifndef SLUT_HAVE_EGL
#define SLUT_HAVE_EGL 0
#endif
#ifndef SLUT_EGL_DLOPEN
#define SLUT_EGL_DLOPEN 0
#endif

#if SLUT_HAVE_EGL
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#if SLUT_EGL_DLOPEN
#include <dlfcn.h>
#endif

namespace gpu_harness {

#define SLUT_GL_FUNCTIONS(X)                                                               \
    X(PFNGLGETSTRINGPROC, glGetString)                                                     \
    X(PFNGLGETERRORPROC, glGetError)                                                       \
    X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                                 \
    X(PFNGLCREATESHADERPROC, glCreateShader)                                               \
    X(PFNGLSHADERSOURCEPROC, glShaderSource)                                               \
    X(PFNGLCOMPILESHADERPROC, glCompileShader)                                             \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                                 \
    X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                                       \
    X(PFNGLDELETESHADERPROC, glDeleteShader)                                               \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                             \
    X(PFNGLATTACHSHADERPROC, glAttachShader)                                               \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                                 \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                               \
    X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                                     \
    X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                             \
    X(PFNGLUSEPROGRAMPROC, glUseProgram)                                                   \
    X(PFNGLGETACTIVEUNIFORMPROC, glGetActiveUniform)                                       \
    X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                                   \
    X(PFNGLUNIFORM1IPROC, glUniform1i)                                                     \
    X(PFNGLGENTEXTURESPROC, glGenTextures)                                                 \
    X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                                           \
    X(PFNGLBINDTEXTUREPROC, glBindTexture)                                                 \
    X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                                             \
    X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                                                   \
    X(PFNGLTEXIMAGE3DPROC, glTexImage3D)                                                   \
    X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                                             \
    X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                                 \
    X(PFNGLGENBUFFERSPROC, glGenBuffers)                                                   \
    X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                             \
    X(PFNGLBINDBUFFERPROC, glBindBuffer)                                                   \
    X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)                                           \
    X(PFNGLBUFFERDATAPROC, glBufferData)                                                   \
    X(PFNGLGETBUFFERSUBDATAPROC, glGetBufferSubData)                                       \
    X(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute)                                         \
    X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier)                                             \
    X(PFNGLFINISHPROC, glFinish)                                                           \
    X(PFNGLUNIFORM1FPROC, glUniform1f)                                                     \
    X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                                         \
    X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                                   \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                         \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                               \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)                           \
    X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                                         \
    X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                                   \
    X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                                         \
    X(PFNGLVIEWPORTPROC, glViewport)                                                       \
    X(PFNGLDRAWARRAYSPROC, glDrawArrays)                                                   \
    X(PFNGLREADPIXELSPROC, glReadPixels)

// The EGL entry points the context needs.
#define SLUT_EGL_FUNCTIONS(X)                                                              \
    X(PFNEGLQUERYSTRINGPROC, eglQueryString)                                               \
    X(PFNEGLGETPROCADDRESSPROC, eglGetProcAddress)                                         \
    X(PFNEGLINITIALIZEPROC, eglInitialize)                                                 \
    X(PFNEGLTERMINATEPROC, eglTerminate)                                                   \
    X(PFNEGLGETERRORPROC, eglGetError)                                                     \
    X(PFNEGLBINDAPIPROC, eglBindAPI)                                                       \
    X(PFNEGLCREATECONTEXTPROC, eglCreateContext)                                           \
    X(PFNEGLDESTROYCONTEXTPROC, eglDestroyContext)                                         \
    X(PFNEGLMAKECURRENTPROC, eglMakeCurrent)

struct Egl {
#define SLUT_EGL_MEMBER(type, name) type name = nullptr;
    SLUT_EGL_FUNCTIONS(SLUT_EGL_MEMBER)
#undef SLUT_EGL_MEMBER
};

// Fills `egl`; "" on success, else why not. Linked: the library's own functions. With
// SLUT_EGL_DLOPEN: from libEGL.so.1 (the library stays loaded for the process).
inline std::string load_egl(Egl &egl) {
#if SLUT_EGL_DLOPEN
    void *library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        const char *e = dlerror();
        return std::string("libEGL.so.1 could not be loaded (") + (e ? e : "dlopen failed") +
               "; Debian: libegl1 and libegl-mesa0)";
    }
#define SLUT_EGL_LOAD(type, name)                                                          \
    egl.name = reinterpret_cast<type>(dlsym(library, #name));                              \
    if (!egl.name) return "libEGL.so.1 has no " #name;
    SLUT_EGL_FUNCTIONS(SLUT_EGL_LOAD)
#undef SLUT_EGL_LOAD
#else
#define SLUT_EGL_LINK(type, name) egl.name = &::name;
    SLUT_EGL_FUNCTIONS(SLUT_EGL_LINK)
#undef SLUT_EGL_LINK
#endif
    return "";
}

struct Gl {
#define SLUT_GL_MEMBER(type, name) type name = nullptr;
    SLUT_GL_FUNCTIONS(SLUT_GL_MEMBER)
#undef SLUT_GL_MEMBER
};

// One surfaceless EGL display and OpenGL 4.3 core context for the whole process.
struct GpuContext {
    bool ok = false;
    std::string why_not; // when !ok
    std::string renderer;
    Gl gl;
    Egl egl;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;

    GpuContext() {
        why_not = load_egl(egl);
        if (!why_not.empty()) return;
        const char *client = egl.eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!client || !std::strstr(client, "EGL_MESA_platform_surfaceless")) {
            why_not = "EGL_MESA_platform_surfaceless is not available (install libegl-mesa0 and "
                      "libgl1-mesa-dri)";
            return;
        }
        auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            egl.eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!get_platform_display) {
            why_not = "eglGetPlatformDisplayEXT is missing";
            return;
        }
        display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display == EGL_NO_DISPLAY || !egl.eglInitialize(display, &major, &minor)) {
            why_not = "no surfaceless EGL display could be initialised (EGL error 0x" + hex(egl.eglGetError()) +
                      "; is libgl1-mesa-dri installed?)";
            return;
        }
        if (!egl.eglBindAPI(EGL_OPENGL_API)) {
            why_not = "eglBindAPI(EGL_OPENGL_API) failed";
            return;
        }
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
        context = egl.eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context == EGL_NO_CONTEXT) {
            why_not = "no OpenGL 4.3 core context (EGL error 0x" + hex(egl.eglGetError()) + ")";
            return;
        }
        if (!egl.eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            why_not = "eglMakeCurrent without a surface failed (EGL_KHR_surfaceless_context?)";
            return;
        }
#define SLUT_GL_LOAD(type, name)                                                           \
    gl.name = reinterpret_cast<type>(egl.eglGetProcAddress(#name));                        \
    if (!gl.name) {                                                                        \
        why_not = "OpenGL entry point " #name " is missing";                               \
        return;                                                                            \
    }
        SLUT_GL_FUNCTIONS(SLUT_GL_LOAD)
#undef SLUT_GL_LOAD
        renderer = std::string(reinterpret_cast<const char *>(gl.glGetString(GL_RENDERER))) + " | " +
                   reinterpret_cast<const char *>(gl.glGetString(GL_VERSION));
        ok = true;
    }
    ~GpuContext() {
        if (display != EGL_NO_DISPLAY) {
            egl.eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context != EGL_NO_CONTEXT) egl.eglDestroyContext(display, context);
            egl.eglTerminate(display);
        }
    }
    static std::string hex(EGLint e) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(e));
        return buf;
    }
};

inline GpuContext &gpu() {
    static GpuContext context;
    return context;
}

// Compiles the given stages (type, source) and links them into one program; "" on
// success, else the log.
inline std::string build_program_stages(const Gl &gl, const std::vector<std::pair<GLenum, std::string>> &stages,
                                        GLuint *program) {
    std::vector<GLuint> shaders;
    std::string error;
    for (const auto &stage : stages) {
        GLuint shader = gl.glCreateShader(stage.first);
        const char *text = stage.second.c_str();
        gl.glShaderSource(shader, 1, &text, nullptr);
        gl.glCompileShader(shader);
        GLint ok = 0;
        gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        shaders.push_back(shader);
        if (!ok) {
            std::vector<char> log(16384, '\0');
            gl.glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
            error = std::string("compile failed:\n") + log.data();
            break;
        }
    }
    if (error.empty()) {
        *program = gl.glCreateProgram();
        for (GLuint shader : shaders) gl.glAttachShader(*program, shader);
        gl.glLinkProgram(*program);
        GLint ok = 0;
        gl.glGetProgramiv(*program, GL_LINK_STATUS, &ok);
        if (!ok) {
            std::vector<char> log(16384, '\0');
            gl.glGetProgramInfoLog(*program, static_cast<GLsizei>(log.size()), nullptr, log.data());
            gl.glDeleteProgram(*program);
            error = std::string("link failed:\n") + log.data();
        }
    }
    for (GLuint shader : shaders) gl.glDeleteShader(shader);
    return error;
}

// Compiles and links one compute shader; "" on success, else the log.
inline std::string build_program(const Gl &gl, const std::string &source, GLuint *program) {
    return build_program_stages(gl, {{GL_COMPUTE_SHADER, source}}, program);
}

// A table as an R32F texture (width x height, or x depth for depth > 0), bound to the active
// unit: GL_LINEAR without mipmaps and CLAMP_TO_EDGE (what the hardware-filter paths need; the
// texelFetch paths ignore both).
inline GLuint make_r32f_texture(const Gl &gl, const std::vector<float> &texels, int width, int height, int depth) {
    const GLenum target = depth > 0 ? GL_TEXTURE_3D : GL_TEXTURE_2D;
    GLuint texture = 0;
    gl.glGenTextures(1, &texture);
    gl.glBindTexture(target, texture);
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (depth > 0)
        gl.glTexImage3D(target, 0, GL_R32F, width, height, depth, 0, GL_RED, GL_FLOAT, texels.data());
    else
        gl.glTexImage2D(target, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, texels.data());
    gl.glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    gl.glTexParameteri(target, GL_TEXTURE_MAX_LEVEL, 0);
    return texture;
}

} // namespace gpu_harness

#endif // SLUT_HAVE_EGL
