// Reading an input file whole (a scene, an OBJ, a TetGen file), refusing what is not a regular
// file (a folder, /dev/zero, a pipe: read as one, they are empty or never end) and what is larger
// than the caller's limit, with the file and the limit named.
#pragma once

#include <tandem/types.h>

#include <cstdint>
#include <string>

namespace tandem {

// `what` names the kind of file in messages ("scene file", "OBJ file"); `limitName` the Limits
// field the caller can raise ("Limits::maxSceneFileBytes").
Result<std::string> readInputFile(const std::string& path, int64_t maxBytes, const char* what, const char* limitName);

}  // namespace tandem
