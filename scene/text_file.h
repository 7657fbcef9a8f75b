// A whole text file read into memory, with the errors the input loaders report.
#pragma once

#include <string>

#include "pipeline/status.h"

namespace rast {

// Fails, naming `path`, for a directory, a file that cannot be opened, or a read error.
Status readTextFile(const std::string& path, std::string& text);

}  // namespace rast
