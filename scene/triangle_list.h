// Window-space triangle lists: a text file with one triangle per line,
//   x0 y0 z0 x1 y1 z1 x2 y2 z2
// in pixels (origin top-left, y down, pixel centres at +0.5) and depth in [0, 1]. Blank lines and
// lines starting with '#' are skipped.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "pipeline/status.h"
#include "shaders_cpp/window_space.h"

namespace rast {

// Three vertices per triangle. Errors name the file and line.
Status parseTriangleList(std::string_view text, const std::string& name,
                         std::vector<WindowVertex>& out);
Status loadTriangleList(const std::string& path, std::vector<WindowVertex>& out);

}  // namespace rast
