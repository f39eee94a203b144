// Whether the suite runs shortened (TANDEM_SHORT_TESTS=1: the sanitizer build, scripts/sanitize.sh),
// where the longest tests run a part of their scene and skip what needs the whole.
#pragma once

#include <cstdlib>
#include <string_view>

namespace tandem {

inline bool shortTests() {
  const char* text = std::getenv("TANDEM_SHORT_TESTS");
  return text != nullptr && std::string_view(text) == "1";
}

}  // namespace tandem
