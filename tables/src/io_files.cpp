// scatterlut runtime — table files on disk: bounded reads that refuse anything but a regular
// file, and atomic writes (a hidden temporary beside the final name, fsync, rename) whose
// temporaries a signal handler can remove (remove_temporaries_in_progress).
#include "scatterlut/io.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <limits>
#include <system_error>

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace scatterlut {

namespace detail {

std::vector<uint8_t> read_file(const std::string &path, uint64_t max_bytes, const char *expected) {
    // O_NONBLOCK: opening a FIFO (or a device) must not wait for a writer; only a regular
    // file is read, and its size is checked before anything is allocated.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) throw LoadError(path + ": cannot open for reading: " + std::strerror(errno));
    struct FdGuard {
        int fd;
        ~FdGuard() { ::close(fd); }
    } guard{fd};
    struct stat st;
    if (::fstat(fd, &st) != 0) throw LoadError(path + ": cannot stat: " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw LoadError(path + ": is a directory, expected " + expected);
    if (!S_ISREG(st.st_mode))
        throw LoadError(path + ": is not a regular file (a FIFO, socket or device), expected " + expected);
    if (static_cast<uint64_t>(st.st_size) > max_bytes)
        throw LoadError(path + ": " + std::to_string(st.st_size) + " bytes, more than the " +
                        std::to_string(max_bytes) + " expected of " + expected);
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    // The size comes from the file system, not from the file's contents.
    std::vector<uint8_t> bytes(static_cast<size_t>(st.st_size));
    size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t r = ::read(fd, bytes.data() + got, bytes.size() - got);
        if (r < 0) {
            if (errno == EINTR) continue;
            throw LoadError(path + ": read error: " + std::strerror(errno));
        }
        if (r == 0) break; // shrank while reading: the decoder reports truncation
        got += static_cast<size_t>(r);
    }
    bytes.resize(got);
    return bytes;
}

std::vector<uint8_t> read_file(const std::string &path) {
    return read_file(path, std::numeric_limits<uint64_t>::max(), "a table file");
}

} // namespace detail

namespace {

// The temporary files of the writes in progress, for remove_temporaries_in_progress (a
// signal handler: it may only read these slots and unlink). A slot is claimed before its
// path is written and published (`ready`) after, so the handler never reads a half-written
// path. More concurrent writes than slots are still atomic, only not cleaned up on a signal.
struct TemporaryFileSlot {
    std::atomic<bool> claimed{false};
    std::atomic<bool> ready{false};
    char path[4096];
};
constexpr int kTemporaryFileSlots = 16;
TemporaryFileSlot g_temporary_files[kTemporaryFileSlots];

TemporaryFileSlot *register_temporary_file(const std::string &path) {
    if (path.size() >= sizeof(TemporaryFileSlot::path)) return nullptr;
    for (TemporaryFileSlot &slot : g_temporary_files) {
        bool expected = false;
        if (!slot.claimed.compare_exchange_strong(expected, true)) continue;
        std::memcpy(slot.path, path.c_str(), path.size() + 1);
        slot.ready.store(true);
        return &slot;
    }
    return nullptr;
}

void release_temporary_file(TemporaryFileSlot *slot) {
    if (!slot) return;
    slot->ready.store(false);
    slot->claimed.store(false);
}

static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs lock-free flags");

} // namespace

void remove_temporaries_in_progress() noexcept {
    for (TemporaryFileSlot &slot : g_temporary_files)
        if (slot.ready.load()) (void)::unlink(slot.path);
}

namespace {

// The directory part of path (the temporary file must be on the same file system).
std::string directory_of(const std::string &path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

// Makes a rename in `dir` durable (best effort: some file systems refuse).
void sync_directory(const std::string &dir) {
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        (void)::fsync(dfd);
        ::close(dfd);
    }
}

struct WrittenTemporary {
    std::string tmp;
    TemporaryFileSlot *slot = nullptr;
};

// Writes bytes to a new hidden temporary beside path, fsyncs and closes it; the temporary is
// registered for remove_temporaries_in_progress until the caller renames or unlinks it and
// releases the slot. On failure nothing is left behind and std::system_error names path.
WrittenTemporary write_temporary(const std::string &path, const std::vector<uint8_t> &bytes) {
    const std::string dir = directory_of(path);
    const size_t slash = path.find_last_of('/');
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    if (base.empty() || base == "." || base == "..")
        throw std::system_error(EISDIR, std::generic_category(), path + ": not a file name");

    static std::atomic<unsigned> counter{0};
    // The name is registered before the file exists, so a SIGINT or SIGTERM handler that calls
    // remove_temporaries_in_progress (the scatterlut command's does) removes it at any moment
    // until the rename. (A name taken already carries this PID: a dead process's leftover.)
    std::string tmp;
    TemporaryFileSlot *slot = nullptr;
    int fd = -1;
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
        tmp = dir + "/." + base.substr(0, 180) + ".tmp-" + std::to_string(::getpid()) + "-" +
              std::to_string(counter.fetch_add(1));
        slot = register_temporary_file(tmp);
        fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666); // umask applies
        if (fd >= 0) break;
        const int err = errno;
        release_temporary_file(slot);
        if (err != EEXIST)
            throw std::system_error(err, std::generic_category(),
                                    path + ": cannot create a temporary file in '" + dir + "'");
    }
    if (fd < 0)
        throw std::system_error(EEXIST, std::generic_category(),
                                path + ": cannot create a temporary file in '" + dir + "'");

    auto fail = [&](int err, const std::string &what) {
        if (fd >= 0) ::close(fd);
        ::unlink(tmp.c_str());
        release_temporary_file(slot);
        throw std::system_error(err, std::generic_category(), path + ": " + what);
    };
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            fail(errno, "write failed (previous file left intact)");
        }
        done += static_cast<size_t>(w);
    }
    if (::fsync(fd) != 0) fail(errno, "fsync failed (previous file left intact)");
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0) fail(errno, "close failed (previous file left intact)");
    return {tmp, slot};
}

} // namespace

void write_file_atomic(const std::string &path, const std::vector<uint8_t> &bytes) {
    WrittenTemporary t = write_temporary(path, bytes);
    if (::rename(t.tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(t.tmp.c_str());
        release_temporary_file(t.slot);
        throw std::system_error(err, std::generic_category(), path + ": cannot rename the temporary file over it");
    }
    release_temporary_file(t.slot);
    sync_directory(directory_of(path));
}

struct AtomicFileSet::Pending {
    std::string path, tmp;
    TemporaryFileSlot *slot = nullptr;
};

AtomicFileSet::AtomicFileSet() = default;

AtomicFileSet::~AtomicFileSet() {
    for (Pending &p : pending_) {
        ::unlink(p.tmp.c_str());
        release_temporary_file(p.slot);
    }
}

void AtomicFileSet::add(const std::string &path, const std::vector<uint8_t> &bytes) {
    pending_.reserve(pending_.size() + 1); // no allocation between the write and the push
    // A final name that is a directory would fail only at its rename, after earlier files
    // of the set were renamed: refused here, while nothing has moved.
    struct stat st;
    if (::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throw std::system_error(EISDIR, std::generic_category(),
                                path + ": is a directory, cannot write the file there (nothing of this set renamed)");
    WrittenTemporary t = write_temporary(path, bytes);
    pending_.push_back(Pending{path, t.tmp, t.slot});
}

void AtomicFileSet::commit() {
    // The renames run with SIGINT, SIGTERM and SIGHUP blocked (this thread): a handler that
    // ends the process must not cut the set in two. A signal that arrives meanwhile is
    // delivered once the last rename is done.
    sigset_t terminating, previous;
    sigemptyset(&terminating);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&terminating, sig);
    pthread_sigmask(SIG_BLOCK, &terminating, &previous);
    struct Restore {
        sigset_t *mask;
        ~Restore() { pthread_sigmask(SIG_SETMASK, mask, nullptr); }
    } restore{&previous};
    std::vector<std::string> dirs;
    dirs.reserve(pending_.size());
    while (!pending_.empty()) {
        Pending &p = pending_.front();
        if (::rename(p.tmp.c_str(), p.path.c_str()) != 0)
            throw std::system_error(errno, std::generic_category(),
                                    p.path + ": cannot rename the temporary file over it (the files before it in "
                                             "the set are renamed already)");
        release_temporary_file(p.slot);
        if (std::find(dirs.begin(), dirs.end(), directory_of(p.path)) == dirs.end()) dirs.push_back(directory_of(p.path));
        pending_.erase(pending_.begin());
    }
    for (const std::string &d : dirs) sync_directory(d);
}

} // namespace scatterlut
