// SPDX-License-Identifier: MIT
// Placeholder until the EGL renderer lands: fails with a clear message (the CLI exits with status 2).
#include "render_hook.h"

namespace supermodal::editor
{

Status render_screenshot(const EditorSession&, EditorUi&, const std::string& png_path, int, int)
{
    return Error{png_path, "",
                 "cannot write a screenshot: the renderer (supermodal_render, EGL) is not linked into "
                 "supermodal-editor yet"};
}

} // namespace supermodal::editor
