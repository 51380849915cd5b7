// SPDX-License-Identifier: MIT
#include "io/ply_header.h"

#include <algorithm>
#include <iterator>
#include <sstream>
#include <vector>

namespace supermodal
{
namespace
{

constexpr std::streamsize k_max_header_bytes = 1 << 20;

std::vector<std::string> split(const std::string& line)
{
    std::istringstream s(line);
    std::vector<std::string> words;
    for (std::string w; s >> w;)
        words.push_back(w);
    return words;
}

bool is_count(const std::string& word)
{
    return !word.empty() && word.size() <= 10 &&
           std::all_of(word.begin(), word.end(), [](unsigned char c) { return c >= '0' && c <= '9'; });
}

bool is_text(const std::string& line, bool any_utf8)
{
    return std::all_of(line.begin(), line.end(), [&](unsigned char c) {
        return (c >= 0x20 && c < 0x7f) || c == '\t' || c == '\r' || (any_utf8 && c >= 0x80);
    });
}

// The scalar types of the PLY format, with the sized aliases assimp also reads.
bool is_ply_type(const std::string& t)
{
    static const char* const types[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                        "float", "double", "int8",    "uint8",  "int16", "uint16",
                                        "int32", "uint32", "float32", "float64"};
    return std::any_of(std::begin(types), std::end(types), [&](const char* x) { return t == x; });
}

std::string at(int line, const std::string& what)
{
    return "PLY header line " + std::to_string(line) + ": " + what;
}

} // namespace

bool looks_like_ply(std::istream& in)
{
    // Three bytes, whatever follows: assimp's PLY reader also takes "ply" followed by binary junk.
    char magic[3] = {};
    in.read(magic, 3);
    return in.gcount() == 3 && magic[0] == 'p' && magic[1] == 'l' && magic[2] == 'y';
}

std::optional<std::string> ply_header_problem(std::istream& in)
{
    std::string line;
    std::streamsize read = 0;
    int number = 0;
    bool format = false;
    std::vector<std::string> elements; // declared so far: assimp 5.2 frees memory it does not own
                                       // when a name comes twice (mesh fuzz, a bad-free)
    while (std::getline(in, line)) {
        ++number;
        read += static_cast<std::streamsize>(line.size()) + 1;
        if (read > k_max_header_bytes)
            return at(number, "no end_header in the first 1 MiB");
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (number == 1) {
            if (line != "ply")
                return at(1, "expected \"ply\"");
            continue;
        }
        const std::vector<std::string> w = split(line);
        const bool free_text = !w.empty() && (w[0] == "comment" || w[0] == "obj_info");
        if (!is_text(line, free_text))
            return at(number, "not text (a byte outside printable ASCII)");
        if (w.empty() || free_text)
            continue;
        if (w[0] == "end_header")
            return format ? std::nullopt : std::optional<std::string>(at(number, "no format line before it"));
        if (w[0] == "format") {
            if (format)
                return at(number, "a second format line");
            if (w.size() != 3 ||
                (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
                return at(number, "expected \"format ascii|binary_little_endian|binary_big_endian VERSION\"");
            format = true;
        } else if (w[0] == "element") {
            if (w.size() != 3 || !is_count(w[2]))
                return at(number, "expected \"element NAME COUNT\" with a whole COUNT");
            if (std::find(elements.begin(), elements.end(), w[1]) != elements.end())
                return at(number, "element \"" + w[1] + "\" declared twice");
            elements.push_back(w[1]);
        } else if (w[0] == "property") {
            const bool scalar = w.size() == 3 && is_ply_type(w[1]);
            const bool list = w.size() == 5 && w[1] == "list" && is_ply_type(w[2]) && is_ply_type(w[3]);
            if (!scalar && !list)
                return at(number,
                          "expected \"property TYPE NAME\" or \"property list TYPE TYPE NAME\" "
                          "(TYPE: char, uchar, short, ushort, int, uint, float, double or a sized alias)");
            if (elements.empty())
                return at(number, "a property before any element");
        } else {
            return at(number, "unknown keyword \"" + w[0] + "\"");
        }
    }
    return at(number, "the file ends before end_header");
}

} // namespace supermodal
