// SPDX-License-Identifier: MIT
// A strict check of a PLY file's text header before assimp reads it: Debian's assimp 5.2 loops forever
// on some malformed headers (found by tests/fuzz/mesh_fuzz.cpp), so a header we cannot read is refused
// with its line number instead.
#pragma once

#include <istream>
#include <optional>
#include <string>

namespace supermodal
{

/// True when the stream starts with "ply" (assimp takes that as PLY); reads from the current position.
[[nodiscard]] bool looks_like_ply(std::istream& in);
/// What is wrong with the PLY header read from `in` (from its start), or nothing: "line N: ...". Checks
/// the magic line, that header lines are printable text (comments may hold any UTF-8), the format line,
/// that every element has a name and a whole count, that properties name a type and a name, and that
/// "end_header" comes within 1 MiB.
[[nodiscard]] std::optional<std::string> ply_header_problem(std::istream& in);

} // namespace supermodal
