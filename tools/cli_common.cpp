// SPDX-License-Identifier: MIT
#include "cli_common.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace supermodal::cli
{

void print_error(const std::string& message)
{
    std::fprintf(stderr, "supermodal: %s\n", message.c_str());
}

std::string check_writable(const std::string& path)
{
    namespace fs = std::filesystem;
    const fs::path p(path);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        return path + ": directory " + dir.string() + " does not exist";
    if (fs::is_directory(p, ec))
        return path + ": is a directory, expected a file name";
    if (::access(dir.c_str(), W_OK) != 0)
        return path + ": directory " + dir.string() + " is not writable";
    return {};
}

std::string write_file_atomically(const std::string& path, const std::string& text)
{
    const std::string tmp = path + ".tmp." + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out)
            return path + ": cannot open for writing";
        out << text;
        out.flush();
        if (!out) {
            std::remove(tmp.c_str());
            return path + ": write failed";
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        return path + ": " + ec.message();
    }
    return {};
}

std::string json_text(const nlohmann::json& j)
{
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json to_json(const Vec3& v)
{
    return nlohmann::json::array({v.x, v.y, v.z});
}
nlohmann::json to_json(const Quat& q)
{
    return nlohmann::json::array({q.w, q.x, q.y, q.z});
}

const char* motion_name(MotionType motion)
{
    switch (motion) {
    case MotionType::Static:
        return "static";
    case MotionType::Kinematic:
        return "kinematic";
    case MotionType::Dynamic:
        return "dynamic";
    }
    return "unknown";
}

} // namespace supermodal::cli
