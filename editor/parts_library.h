// SPDX-License-Identifier: MIT
// The Parts library: the part files of a folder (samples/parts/ by default), each with a thumbnail drawn
// offscreen by the engine's renderer once and kept in memory and, keyed by the file's content hash, on
// disk, so a later start reads the PNG instead of drawing it again.
#pragma once

#include "supermodal/result.h"

#include <cstdint>
#include <string>
#include <vector>

namespace supermodal::editor
{

/// How thumbnails are drawn and where they are kept.
struct ThumbnailDef {
    int size = 96;         ///< Width and height of a thumbnail [px], in [16, 1024].
    std::string cache_dir; ///< Folder of cached PNGs (made when missing); empty: memory only.
};

/// One part file of the library.
struct PartEntry {
    std::string path;          ///< The file.
    std::string label;         ///< Its name without ".json" (what the panel shows).
    uint64_t hash = 0;         ///< FNV-1a 64 of the file's bytes: the disk cache's key.
    int width = 0;             ///< Thumbnail size [px]; 0 until drawn (or when it cannot be).
    int height = 0;            ///< [px]
    std::vector<uint8_t> rgba; ///< Thumbnail pixels, rows top to bottom, 4 bytes each.
    bool from_cache = false;   ///< Read from the disk cache instead of drawn.
    std::string error;         ///< Why it has no thumbnail (an invalid file, no renderer); empty if fine.
};

class PartsLibrary
{
  public:
    /// Lists the *.json files of `folder` (sorted by name) and hashes them; no thumbnail is drawn yet.
    /// Fails, keeping what it had, for a folder that cannot be read.
    Status scan(const std::string& folder, const ThumbnailDef& def = {});
    /// Draws (or reads from the disk cache) every thumbnail not yet there; returns how many were drawn
    /// with the renderer. Each is tried once: a failure is kept in its entry's `error`.
    int render_pending();
    [[nodiscard]] bool pending() const { return m_pending; }

    [[nodiscard]] const std::vector<PartEntry>& entries() const { return m_entries; }
    [[nodiscard]] const std::string& folder() const { return m_folder; }
    [[nodiscard]] const ThumbnailDef& settings() const { return m_def; }
    /// Counts scans: a host's textures made for an older scan are stale [-].
    [[nodiscard]] uint64_t generation() const { return m_generation; }
    /// The entry whose label or path is `name`, or null.
    [[nodiscard]] const PartEntry* find(const std::string& name) const;

  private:
    std::string m_folder;
    ThumbnailDef m_def;
    std::vector<PartEntry> m_entries;
    bool m_pending = false;
    uint64_t m_generation = 0;
};

/// FNV-1a 64 of a file's bytes; fails when it cannot be read.
[[nodiscard]] Result<uint64_t> file_content_hash(const std::string& path);

/// A part file's thumbnail key: its bytes' hash mixed with the keys of the files its scene reads
/// (includes, recursively, and render meshes), so a thumbnail is drawn again when any of them changes.
/// Fails when the part file itself cannot be read.
[[nodiscard]] Result<uint64_t> part_content_hash(const std::string& path);

/// Draws a part file's bodies offscreen at size × size pixels, framed from the default orbit camera's
/// angles (yaw 30°, pitch 20°), without the ground grid; into `entry`'s pixels. Fails without the
/// renderer or for an invalid file.
Status render_part_thumbnail(PartEntry& entry, int size);

} // namespace supermodal::editor
