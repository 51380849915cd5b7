// SPDX-License-Identifier: MIT
// The loader's verdict for tests/schema/scene_schema_test.py, which compares it with the JSON Schema's.
//   scene_probe check        one scene per line on stdin (compact JSON); per line on stdout "ok", or
//                            "error: " and the loader's message (parse_scene; paths relative to the
//                            working directory)
//   scene_probe resave IN OUT   load_scene(IN), then save_scene to OUT (the scene writer's output)
#include "supermodal/scene.h"

#include <cstdio>
#include <iostream>
#include <string>

namespace sm = supermodal;

namespace
{

int check_lines()
{
    std::string line;
    while (std::getline(std::cin, line)) {
        const sm::Result<sm::Scene> scene = sm::parse_scene(line, "<stdin>");
        if (scene) {
            std::cout << "ok\n";
            continue;
        }
        std::string message = scene.error().message();
        for (char& c : message)
            if (c == '\n' || c == '\r')
                c = ' ';
        std::cout << "error: " << message << '\n';
    }
    std::cout.flush();
    return 0;
}

int resave(const std::string& in, const std::string& out)
{
    const sm::Result<sm::Scene> scene = sm::load_scene(in);
    if (!scene) {
        std::fprintf(stderr, "%s\n", scene.error().message().c_str());
        return 2;
    }
    if (const sm::Status saved = sm::save_scene(*scene, out); !saved) {
        std::fprintf(stderr, "%s\n", saved.error().message().c_str());
        return 1;
    }
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "check" && argc == 2)
        return check_lines();
    if (command == "resave" && argc == 4)
        return resave(argv[2], argv[3]);
    std::fprintf(stderr, "usage: scene_probe check < scenes.jsonl | scene_probe resave IN OUT\n");
    return 2;
}
