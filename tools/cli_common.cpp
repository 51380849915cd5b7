// SPDX-License-Identifier: MIT
#include "cli_common.h"

#include <CLI/CLI.hpp>
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
    // A device or pipe (/dev/null, /dev/stdout) takes the text as it is: renaming over it would replace
    // the device with a file.
    std::error_code status_ec;
    const auto status = std::filesystem::status(path, status_ec);
    if (!status_ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
        !std::filesystem::is_directory(status)) {
        std::ofstream out(path, std::ios::binary);
        out << text;
        out.flush();
        return out ? std::string{} : path + ": write failed";
    }
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

std::string parse_set_options(const std::vector<std::string>& sets, std::vector<SceneOverride>& out)
{
    for (const std::string& set : sets) {
        const size_t eq = set.find('=');
        if (eq == std::string::npos)
            return "--set " + set + ": expected /json/pointer=value, as in --set /settings/dt=0.001";
        SceneOverride o{set.substr(0, eq), set.substr(eq + 1)};
        // Not JSON: a plain word such as a material name, written as a JSON string. Bytes that are not
        // UTF-8 become U+FFFD instead of an exception, as in json_text().
        if (!nlohmann::json::accept(o.value))
            o.value = nlohmann::json(o.value).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        out.push_back(std::move(o));
    }
    return {};
}

Result<Scene> load_scene_with(const std::string& path, const std::vector<std::string>& sets)
{
    std::vector<SceneOverride> overrides;
    if (std::string error = parse_set_options(sets, overrides); !error.empty())
        return Error{"", "", error};
    return load_scene(path, overrides);
}

void add_set_option(CLI::App& cmd, std::vector<std::string>& sets)
{
    cmd.add_option("--set", sets,
                   "Set a scene value before it is checked: /json/pointer=value, the value JSON or else a "
                   "string (--set /bodies/0/density=500); repeatable, applied in order")
        ->allow_extra_args(false)
        ->take_all();
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
