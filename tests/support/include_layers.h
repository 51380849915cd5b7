// SPDX-License-Identifier: MIT
// Reads the #include lines of a source tree laid out as <root>/<area>/... and reports every include of
// an internal header ("area/file.h") from a higher layer than the including file's own area.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal::test
{

/// The engine's layers, lowest first: a file may include its own layer and those below, never above.
/// core → geometry → the areas (dynamics → contact → modal → constraints: each area may use the ones
/// before it) → world (registry, the systems that walk it, the step) → assets (scene, io, fit) → the
/// C API and render. The library column follows engine/CMakeLists.txt: each library links only those
/// below it, so two areas on one level may include each other only inside one library (capi and render
/// are side by side: each links assets, neither the other).
struct Layer {
    std::string_view area;
    int level;
    std::string_view library;
};
inline constexpr Layer k_engine_layers[] = {
    {"core", 0, "engine"},  {"geometry", 1, "engine"},    {"dynamics", 2, "engine"}, {"contact", 3, "engine"},
    {"modal", 4, "engine"}, {"constraints", 5, "engine"}, {"world", 6, "engine"},    {"scene", 7, "assets"},
    {"io", 7, "assets"},    {"fit", 7, "assets"},         {"capi", 8, "c"},          {"render", 8, "render"},
};

[[nodiscard]] inline const Layer* layer_of(std::string_view area)
{
    for (const Layer& l : k_engine_layers)
        if (l.area == area)
            return &l;
    return nullptr;
}

/// True when a file of `own` may include a header of `theirs`: a lower level, or the same level in the
/// same library.
[[nodiscard]] inline bool may_include(const Layer& own, const Layer& theirs)
{
    return theirs.level < own.level || (theirs.level == own.level && theirs.library == own.library);
}

/// One include that points the wrong way: "engine/src/contact/penalty.h:11: ..." (path relative to root).
struct LayerViolation {
    std::string file; ///< Relative to the root, '/'-separated.
    int line = 0;     ///< 1-based.
    std::string message;
};

/// Every upward include (or one into a sibling library) under `root`, in path order; also files in a
/// folder that has no layer.
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
        const Layer* own = layer_of(area);
        if (own == nullptr) {
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
            const Layer* theirs = layer_of(target);
            if (theirs == nullptr)
                out.push_back({rel, n, "includes '" + target + "/', a folder with no layer"});
            else if (!may_include(*own, *theirs))
                out.push_back({rel, n,
                               "includes " + m[0].str().substr(m[0].str().find('"')) + " (" + target +
                                   ", layer " + std::to_string(theirs->level) + ", library " +
                                   std::string(theirs->library) + ") from " + area + " (layer " +
                                   std::to_string(own->level) + ", library " + std::string(own->library) +
                                   "): " +
                                   (theirs->level > own->level ? "it points up a layer"
                                                               : "a library it does not link")});
        }
    }
    return out;
}

} // namespace supermodal::test
