// SPDX-License-Identifier: MIT
#include "io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace supermodal
{

namespace
{

// A device or pipe (/dev/null, /dev/stdout) takes the bytes as they come: renaming a temporary file over
// it would replace the device with a file.
bool is_special_file(const std::string& path)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    return !ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
           !std::filesystem::is_directory(status);
}

Status write_special_file(const std::string& path, const void* data, size_t size)
{
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr)
        return Error{path, "", std::string("cannot open: ") + std::strerror(errno)};
    const bool written = std::fwrite(data, 1, size, file) == size && std::fflush(file) == 0;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed)
        return Error{path, "", std::string("cannot write: ") + std::strerror(errno)};
    return {};
}

} // namespace

Status write_file_atomically(const std::string& path, const void* data, size_t size)
{
    if (is_special_file(path))
        return write_special_file(path, data, size);
    // Same folder, so the rename stays on one file system; the pid keeps two writers apart.
    const std::string temp = path + ".tmp." + std::to_string(::getpid());
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (file == nullptr)
        return Error{path, "",
                     std::string("cannot create a temporary file beside it: ") + std::strerror(errno)};
    const bool written =
        std::fwrite(data, 1, size, file) == size && std::fflush(file) == 0 && ::fsync(::fileno(file)) == 0;
    const int write_errno = errno;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) {
        std::remove(temp.c_str());
        return Error{path, "", std::string("cannot write: ") + std::strerror(written ? errno : write_errno)};
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::remove(temp.c_str());
        return Error{path, "", "cannot replace the file: " + ec.message()};
    }
    return {};
}

} // namespace supermodal
