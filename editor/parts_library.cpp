// SPDX-License-Identifier: MIT
#include "parts_library.h"

#include "supermodal/scene.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <system_error>

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
#include "supermodal/render.h"
#endif

namespace supermodal::editor
{
namespace
{

namespace fs = std::filesystem;

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
std::string cache_file(const ThumbnailDef& def, const PartEntry& e)
{
    char name[64];
    std::snprintf(name, sizeof name, "%016llx-%d.png", static_cast<unsigned long long>(e.hash), def.size);
    return (fs::path(def.cache_dir) / name).string();
}

bool read_cached(const ThumbnailDef& def, PartEntry& e)
{
    if (def.cache_dir.empty())
        return false;
    std::error_code ec;
    if (!fs::exists(cache_file(def, e), ec))
        return false;
    Result<Image> image = read_png(cache_file(def, e));
    if (!image || image->width != def.size || image->height != def.size)
        return false; // a damaged or foreign file: draw it again
    e.width = image->width;
    e.height = image->height;
    e.rgba = std::move(image->rgba);
    e.from_cache = true;
    return true;
}

/// write_png writes through a temporary file: a reader never finds half a PNG. A cache that cannot be
/// written only costs a redraw next time.
void write_cached(const ThumbnailDef& def, const PartEntry& e)
{
    if (def.cache_dir.empty())
        return;
    std::error_code ec;
    fs::create_directories(def.cache_dir, ec);
    (void)write_png(cache_file(def, e), Image{e.width, e.height, e.rgba});
}
#endif

constexpr uint64_t k_fnv_offset = 1469598103934665603ull; // FNV-1a 64: offset basis and prime
constexpr uint64_t k_fnv_prime = 1099511628211ull;

uint64_t fnv_bytes(uint64_t h, const char* bytes, size_t count)
{
    for (size_t i = 0; i < count; ++i) {
        h ^= static_cast<unsigned char>(bytes[i]);
        h *= k_fnv_prime;
    }
    return h;
}

// The file's bytes, or nothing when it cannot be read.
std::optional<std::string> read_file(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return std::move(text).str();
}

} // namespace

Result<uint64_t> file_content_hash(const std::string& path)
{
    const std::optional<std::string> bytes = read_file(path);
    if (!bytes)
        return Error{path, "", "cannot read the file"};
    return fnv_bytes(k_fnv_offset, bytes->data(), bytes->size());
}

namespace
{

// Includes nest at most this deep when a part's key is made (the loader refuses deeper ones anyway).
constexpr int k_max_key_depth = 16;

// FNV-1a 64 of a file's bytes, then of the keys of the files its scene reads in the order it names
// them ("include" files, bodies' "mesh" files), relative to its folder; nothing when the file cannot be
// read. A reference that cannot be read or parsed adds a zero: loading the part reports it.
std::optional<uint64_t> part_key(const fs::path& path, int depth)
{
    const std::optional<std::string> bytes = read_file(path.string());
    if (!bytes)
        return std::nullopt;
    uint64_t h = fnv_bytes(k_fnv_offset, bytes->data(), bytes->size());
    const nlohmann::json doc = nlohmann::json::parse(*bytes, nullptr, false);
    if (depth >= k_max_key_depth || !doc.is_object())
        return h;
    auto mix = [&h](uint64_t x) {
        char le[8];
        for (int i = 0; i < 8; ++i)
            le[i] = static_cast<char>((x >> (8 * i)) & 0xff);
        h = fnv_bytes(h, le, sizeof le);
    };
    auto refer = [&](const nlohmann::json& list, const char* key, bool nested) {
        if (!list.is_array())
            return;
        for (const nlohmann::json& item : list)
            if (item.is_object() && item.contains(key) && item[key].is_string()) {
                const fs::path child = path.parent_path() / item[key].get<std::string>();
                if (nested) {
                    mix(part_key(child, depth + 1).value_or(0));
                } else {
                    const Result<uint64_t> mesh = file_content_hash(child.string());
                    mix(mesh ? *mesh : 0);
                }
            }
    };
    if (doc.contains("include"))
        refer(doc["include"], "file", true);
    if (doc.contains("bodies"))
        refer(doc["bodies"], "mesh", false);
    return h;
}

} // namespace

Result<uint64_t> part_content_hash(const std::string& path)
{
    if (std::optional<uint64_t> key = part_key(fs::path(path), 0))
        return *key;
    return Error{path, "", "cannot read the file"};
}

Status PartsLibrary::scan(const std::string& folder, const ThumbnailDef& def)
{
    if (!(def.size >= 16 && def.size <= 1024))
        return Error{"", "size", "expected a thumbnail size in [16, 1024] px"};
    std::error_code ec;
    std::vector<PartEntry> entries;
    for (const fs::directory_entry& f : fs::directory_iterator(folder, ec)) {
        if (!f.is_regular_file() || f.path().extension() != ".json")
            continue;
        PartEntry e;
        e.path = f.path().string();
        e.label = f.path().stem().string();
        Result<uint64_t> hash = part_content_hash(e.path);
        if (!hash)
            return hash.error();
        e.hash = *hash;
        entries.push_back(std::move(e));
    }
    if (ec)
        return Error{folder, "", "cannot list the parts folder: " + ec.message()};
    std::sort(entries.begin(), entries.end(),
              [](const PartEntry& a, const PartEntry& b) { return a.label < b.label; });
    m_folder = folder;
    m_def = def;
    m_entries = std::move(entries);
    m_pending = !m_entries.empty();
    ++m_generation;
    return {};
}

int PartsLibrary::render_pending()
{
    if (!m_pending)
        return 0;
    m_pending = false;
    int drawn = 0;
    for (PartEntry& e : m_entries) {
        if (e.width > 0 || !e.error.empty())
            continue;
#ifdef SUPERMODAL_EDITOR_HAS_RENDER
        if (read_cached(m_def, e))
            continue;
#endif
        if (Status status = render_part_thumbnail(e, m_def.size); !status) {
            e.error = status.error().message();
            continue;
        }
        ++drawn;
#ifdef SUPERMODAL_EDITOR_HAS_RENDER
        write_cached(m_def, e);
#endif
    }
    return drawn;
}

const PartEntry* PartsLibrary::find(const std::string& name) const
{
    for (const PartEntry& e : m_entries)
        if (e.label == name || e.path == name)
            return &e;
    return nullptr;
}

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
Status render_part_thumbnail(PartEntry& entry, int size)
{
    Result<Scene> scene = load_scene(entry.path);
    if (!scene)
        return scene.error();
    Result<World> world = build_world(*scene);
    if (!world)
        return world.error();
    RenderDef def = default_render_def();
    def.width = def.height = size;
    def.grid = false; // the part alone, on the sky
    Result<Renderer> renderer = Renderer::create(def);
    if (!renderer)
        return Error{entry.path, "", "cannot draw the thumbnail: " + renderer.error().message()};
    apply_scene_looks(*renderer, *scene, *world);
    const CameraDef camera = frame_bodies(*world, CameraDef{}, 1.0);
    Image image;
    if (Status drawn = renderer->render(*world, camera, image, PoseSource::Current); !drawn)
        return Error{entry.path, "", "cannot draw the thumbnail: " + drawn.error().message()};
    entry.width = image.width;
    entry.height = image.height;
    entry.rgba = std::move(image.rgba);
    return {};
}
#else
Status render_part_thumbnail(PartEntry& entry, int)
{
    return Error{entry.path, "", "no thumbnail: this build has no renderer (SUPERMODAL_RENDER=OFF)"};
}
#endif

} // namespace supermodal::editor
