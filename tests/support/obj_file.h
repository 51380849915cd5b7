// Writes a TriangleMesh as a Wavefront OBJ (positions and triangles): the import, fit and export tests
// make their mesh files this way. 17 significant digits keep every double exact through the text.
#pragma once

#include "supermodal/geometry.h"

#include <cstdio>
#include <fstream>
#include <string>

namespace supermodal::test
{

inline void write_obj_file(const TriangleMesh& m, const std::string& path)
{
    std::ofstream out(path);
    char line[160];
    for (const Vec3& p : m.positions) {
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
        out << line;
    }
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        out << "f " << m.indices[t] + 1 << ' ' << m.indices[t + 1] + 1 << ' ' << m.indices[t + 2] + 1 << '\n';
}

} // namespace supermodal::test
