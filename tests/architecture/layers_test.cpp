// Tests for the engine's layering: no file under engine/src includes a header from a layer above its own.
#include "support/include_layers.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace supermodal::test
{
namespace
{

std::string describe(const std::vector<LayerViolation>& found)
{
    std::string s;
    for (const LayerViolation& v : found)
        s += v.file + ":" + std::to_string(v.line) + ": " + v.message + "\n";
    return s;
}

void write(const std::filesystem::path& path, const std::string& text)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

} // namespace

TEST(Layers, EngineIncludesPointDownOnly)
{
    const std::vector<LayerViolation> found = find_layer_violations(SM_SOURCE_DIR "/engine/src");
    EXPECT_TRUE(found.empty()) << describe(found);
}

TEST(Layers, UpwardIncludeIsReportedWithFileAndLine)
{
    // A tree with one include of each kind: down (ok), sideways within the area (ok), public (ok), up.
    const std::filesystem::path root = std::filesystem::temp_directory_path() / "supermodal_layers_test";
    std::filesystem::remove_all(root);
    write(root / "core/a.h", "#pragma once\n#include <vector>\n");
    write(root / "contact/b.h", "#pragma once\n#include \"core/a.h\"\n#include \"contact/c.h\"\n");
    write(root / "contact/c.h", "#pragma once\n#include \"supermodal/world.h\"\n");
    write(root / "modal/d.cpp",
          "// a modal file\n#include \"modal/e.h\"\n  #include \"world/components.h\"\n");
    write(root / "modal/e.h", "#pragma once\n");
    const std::vector<LayerViolation> found = find_layer_violations(root);
    ASSERT_EQ(found.size(), 1u) << describe(found);
    EXPECT_EQ(found[0].file, "modal/d.cpp");
    EXPECT_EQ(found[0].line, 3);
    EXPECT_NE(found[0].message.find("world/components.h"), std::string::npos) << found[0].message;
    std::filesystem::remove_all(root);
}

TEST(Layers, IncludeIntoASiblingLibraryIsReported)
{
    // capi and render share a level but not a library: neither links the other. scene and io share
    // both, and both may use the engine below them.
    const std::filesystem::path root = std::filesystem::temp_directory_path() / "supermodal_layers_sibling";
    std::filesystem::remove_all(root);
    write(root / "world/w.h", "#pragma once\n");
    write(root / "io/f.h", "#pragma once\n#include \"world/w.h\"\n");
    write(root / "scene/s.cpp", "#include \"io/f.h\"\n");
    write(root / "capi/c.h", "#pragma once\n#include \"scene/s.h\"\n");
    write(root / "render/r.cpp", "#include \"io/f.h\"\n#include \"capi/c.h\"\n");
    const std::vector<LayerViolation> found = find_layer_violations(root);
    ASSERT_EQ(found.size(), 1u) << describe(found);
    EXPECT_EQ(found[0].file, "render/r.cpp");
    EXPECT_EQ(found[0].line, 2);
    EXPECT_NE(found[0].message.find("a library it does not link"), std::string::npos) << found[0].message;
    std::filesystem::remove_all(root);
}

TEST(Layers, FolderWithoutLayerIsReported)
{
    const std::filesystem::path root = std::filesystem::temp_directory_path() / "supermodal_layers_new";
    std::filesystem::remove_all(root);
    write(root / "core/a.h", "#pragma once\n#include \"physics/x.h\"\n");
    write(root / "physics/x.h", "#pragma once\n");
    const std::vector<LayerViolation> found = find_layer_violations(root);
    ASSERT_EQ(found.size(), 2u) << describe(found);
    EXPECT_EQ(found[0].file, "core/a.h");
    EXPECT_EQ(found[0].line, 2);
    EXPECT_EQ(found[1].file, "physics/x.h");
    std::filesystem::remove_all(root);
}

} // namespace supermodal::test
