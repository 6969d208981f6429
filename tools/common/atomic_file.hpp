// tools/common/atomic_file.hpp: the one way every tool and example program of cloudmath
// writes an output file, so that a failed or interrupted run never leaves half a file and
// never damages the file that was there before.
//
//   const std::string error = cloudmath::tools::write_file_atomically("out.png", bytes);
//   if (!error.empty()) { std::fprintf(stderr, "tool: %s\n", error.c_str()); return 1; }
//
// write_file_atomically(path, bytes):
//   1. creates a new temporary file beside the target ("<path>.<pid>-<n>.tmp", O_EXCL, so
//      two runs never share one; same directory, so the rename below cannot cross devices),
//   2. writes every byte (short writes and EINTR retried), optionally fsyncs it,
//   3. closes it (close reports delayed write errors on some file systems),
//   4. renames it over the target: readers see either the old file or the whole new one.
//   Any failure removes the temporary file and leaves the target as it was. The returned
//   message is empty on success, else one line naming the path, the step and the system's
//   reason ("cannot write 'out.png': No space left on device").
//   A target that exists and is not a regular file (/dev/null, /dev/stdout, a FIFO, a
//   device such as /dev/full) is written in place, with every write checked: renaming a
//   file over a device node would replace the node. A directory is refused. A symbolic link
//   to a regular file is followed: the file it names is replaced, the link is kept.
//   The new file gets the permission bits of the file it replaces, or 0666 minus the umask.
//
// check_output_path(path): the same checks without writing, for tools that compute for a
// long time before they write: creates and removes a temporary file beside the target (a
// device is opened for writing and closed). Fails early on a missing or unwritable
// directory; the real write can still fail later (disk full), and is checked then.
//
// POSIX only (open, write, fsync, rename), like the programs that use it.
#ifndef CLOUDMATH_TOOLS_COMMON_ATOMIC_FILE_HPP
#define CLOUDMATH_TOOLS_COMMON_ATOMIC_FILE_HPP

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

namespace cloudmath::tools {

namespace atomic_file_detail {

inline std::string failure(const std::string& what, const std::string& path, int error) {
    return what + " '" + path + "': " + std::strerror(error);
}

// Writes all of data to fd, retrying short writes and EINTR; 0 or the errno of the failure.
inline int write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ::ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (n == 0) return EIO;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return 0;
}

// Where the bytes go: the target itself (not a regular file) or a temporary beside it.
struct destination {
    std::string target;    // the file the rename replaces (a symbolic link resolved)
    bool in_place = false; // write straight into target (a device, FIFO, ...)
    bool exists = false;   // target is an existing regular file
    ::mode_t mode = 0;     // its permission bits, when it exists
    std::string error;     // non-empty: refuse
};

inline destination resolve(const std::string& path) {
    destination d;
    d.target = path;
    if (path.empty()) {
        d.error = "cannot write '': empty path";
        return d;
    }
    struct ::stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno != ENOENT) d.error = failure("cannot write", path, errno);
        return d;  // a new file (a missing directory shows when the temporary is created)
    }
    if (S_ISDIR(st.st_mode)) {
        d.error = failure("cannot write", path, EISDIR);
        return d;
    }
    if (!S_ISREG(st.st_mode)) {
        d.in_place = true;
        return d;
    }
    d.exists = true;
    d.mode = st.st_mode & 07777;
    struct ::stat link {};
    if (::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
        char resolved[PATH_MAX];
        if (::realpath(path.c_str(), resolved) == nullptr) {
            d.error = failure("cannot resolve the link", path, errno);
            return d;
        }
        d.target = resolved;
    }
    return d;
}

// Creates "<target>.<pid>-<n>.tmp" exclusively; returns the descriptor (or -1, errno set).
inline int create_temporary(const std::string& target, std::string& name) {
    static std::atomic<unsigned> counter{0};
    for (int attempt = 0; attempt < 100; ++attempt) {
        name = target + "." + std::to_string(static_cast<long>(::getpid())) + "-" +
               std::to_string(counter.fetch_add(1)) + ".tmp";
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    errno = EEXIST;
    return -1;
}

inline int close_checked(int fd) {
    if (::close(fd) != 0 && errno != EINTR) return errno;  // EINTR: the descriptor is closed
    return 0;
}

inline std::string write_in_place(const std::string& path, std::string_view bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return failure("cannot open", path, errno);
    const int error = write_all(fd, bytes.data(), bytes.size());
    const int close_error = close_checked(fd);
    if (error != 0) return failure("cannot write", path, error);
    if (close_error != 0) return failure("cannot write", path, close_error);
    return {};
}

// fsync of the directory that holds path, so that the rename itself is durable.
inline void sync_directory(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    const int fd = ::open(dir.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);  // best effort: some file systems refuse fsync on directories
    ::close(fd);
}

}  // namespace atomic_file_detail

// See the top of the file. sync: fsync the file before the rename and the directory after.
[[nodiscard]] inline std::string write_file_atomically(const std::string& path, std::string_view bytes,
                                                       bool sync = false) {
    namespace d = atomic_file_detail;
    const d::destination dest = d::resolve(path);
    if (!dest.error.empty()) return dest.error;
    if (dest.in_place) return d::write_in_place(path, bytes);

    std::string tmp;
    const int fd = d::create_temporary(dest.target, tmp);
    if (fd < 0) return d::failure("cannot create a temporary file beside", path, errno);
    const auto fail = [&](const char* what, int error, bool open) {
        if (open) ::close(fd);
        ::unlink(tmp.c_str());
        return d::failure(what, path, error);
    };
    if (dest.exists && ::fchmod(fd, dest.mode) != 0) return fail("cannot set the permissions of", errno, true);
    if (const int error = d::write_all(fd, bytes.data(), bytes.size()); error != 0)
        return fail("cannot write", error, true);
    if (sync && ::fsync(fd) != 0) return fail("cannot sync", errno, true);
    if (const int error = d::close_checked(fd); error != 0) return fail("cannot write", error, false);
    if (::rename(tmp.c_str(), dest.target.c_str()) != 0) return fail("cannot replace", errno, false);
    if (sync) d::sync_directory(dest.target);
    return {};
}

// See the top of the file: empty when path looks writable, else the reason.
[[nodiscard]] inline std::string check_output_path(const std::string& path) {
    namespace d = atomic_file_detail;
    const d::destination dest = d::resolve(path);
    if (!dest.error.empty()) return dest.error;
    if (dest.in_place) {
        const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK);
        if (fd < 0) return d::failure("cannot open", path, errno);
        ::close(fd);
        return {};
    }
    std::string tmp;
    const int fd = d::create_temporary(dest.target, tmp);
    if (fd < 0) return d::failure("cannot create a file beside", path, errno);
    ::close(fd);
    ::unlink(tmp.c_str());
    return {};
}

}  // namespace cloudmath::tools

#endif  // CLOUDMATH_TOOLS_COMMON_ATOMIC_FILE_HPP
