// SPDX-License-Identifier: MIT
// Reads the #include lines of a source tree laid out as <root>/<area>/... and reports every include of
// an internal header ("area/file.h") from a higher layer than the including file's own area.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal::test
{

/// The engine's layers, lowest first: a file may include its own layer and those below, never above.
/// core → geometry → the areas (dynamics → contact → modal → constraints: each area may use the ones
/// before it) → world (registry, the systems that walk it, the step) → the C API → assets (scene, io,
/// fit) → render.
struct Layer {
    std::string_view area;
    int level;
};
inline constexpr Layer k_engine_layers[] = {
    {"core", 0},  {"geometry", 1}, {"dynamics", 2}, {"contact", 3}, {"modal", 4}, {"constraints", 5},
    {"world", 6}, {"capi", 7},     {"scene", 8},    {"io", 8},      {"fit", 8},   {"render", 9},
};

[[nodiscard]] inline std::optional<int> layer_of(std::string_view area)
{
    for (const Layer& l : k_engine_layers)
        if (l.area == area)
            return l.level;
    return std::nullopt;
}

/// One include that points the wrong way: "engine/src/contact/penalty.h:11: ..." (path relative to root).
struct LayerViolation {
    std::string file; ///< Relative to the root, '/'-separated.
    int line = 0;     ///< 1-based.
    std::string message;
};

/// Every upward include under `root`, in path order; also files in a folder that has no layer.
[[nodiscard]] inline std::vector<LayerViolation> find_layer_violations(const std::filesystem::path& root)
{
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root)) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".h" || ext == ".cpp"))
            files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    static const std::regex k_include(R"(^\s*#\s*include\s*"([a-z_0-9]+)/[^"]+")");
    std::vector<LayerViolation> out;
    for (const fs::path& path : files) {
        const std::string rel = fs::relative(path, root).generic_string();
        const std::string area = rel.substr(0, rel.find('/'));
        const std::optional<int> own = layer_of(area);
        if (!own) {
            out.push_back({rel, 0, "folder '" + area + "' has no layer: add it to k_engine_layers"});
            continue;
        }
        std::ifstream in(path);
        std::string text;
        for (int n = 1; std::getline(in, text); ++n) {
            std::smatch m;
            if (!std::regex_search(text, m, k_include))
                continue;
            const std::string target = m[1].str();
            if (target == "supermodal")
                continue; // the public API: any layer may use it
            const std::optional<int> theirs = layer_of(target);
            if (!theirs)
                out.push_back({rel, n, "includes '" + target + "/', a folder with no layer"});
            else if (*theirs > *own)
                out.push_back({rel, n,
                               "includes " + m[0].str().substr(m[0].str().find('"')) + " (" + target +
                                   ", layer " + std::to_string(*theirs) + ") from " + area + " (layer " +
                                   std::to_string(*own) + "): it points up a layer"});
        }
    }
    return out;
}

} // namespace supermodal::test
