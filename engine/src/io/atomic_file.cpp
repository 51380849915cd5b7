// SPDX-License-Identifier: MIT
#include "io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace supermodal
{

Status write_file_atomically(const std::string& path, const void* data, size_t size)
{
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
