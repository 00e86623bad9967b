// libFuzzer target for the generator's text readers: the eval line reader (eval_stream)
// and the scene reader (parse_scene). Built twice (tests/fuzz/run_fuzz_inputs.cmake): with
// -DSLUT_FUZZ_EVAL any byte string is fed to eval as its standard input, and must be
// answered with exactly one valid JSON line per input line (an "error" line for a bad
// one), never a crash, a hang or an unbounded allocation; with -DSLUT_FUZZ_SCENE it is a
// scene file's text, which must give a Scene or a SceneError (file:line:col and the key),
// nothing else. docs/FUZZING.md says how to run them longer.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "embedded_kernels.hpp"
#include "eval.hpp"
#include "scene.hpp"

// scene.cpp's default scene is embedded into the scatterlut executable at build time; the
// fuzzer reads only the text it is given.
namespace scatterlut::embedded {
extern const EmbeddedFile kSceneFiles[] = {{"none.toml", ""}};
extern const std::size_t kSceneFileCount = 0;
} // namespace scatterlut::embedded

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string text(reinterpret_cast<const char *>(data), size);
#ifdef SLUT_FUZZ_EVAL
    std::istringstream in(text);
    std::ostringstream out;
    static const scatterlut::EvalTables no_tables;
    scatterlut::eval_stream(in, out, no_tables);
    // One answer per input line (a last line without '\n' counts), each a JSON object.
    size_t lines = 0;
    for (char c : text) lines += c == '\n';
    if (!text.empty() && text.back() != '\n') ++lines;
    std::istringstream answers(out.str());
    std::string answer;
    size_t answered = 0;
    while (std::getline(answers, answer)) {
        ++answered;
        if (!nlohmann::json::parse(answer).is_object()) std::abort();
    }
    if (answered != lines) std::abort();
#else
    try {
        (void)scatterlut::parse_scene(text, "fuzz.toml");
    } catch (const scatterlut::SceneError &) {
    }
#endif
    return 0;
}
