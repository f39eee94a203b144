// Whether the suite runs shortened (TANDEM_SHORT_TESTS=1: the sanitizer build, scripts/sanitize.sh),
// where the longest tests run a part of their scene and skip what needs the whole.
#pragma once

#include <cstdlib>
#include <initializer_list>
#include <string_view>
#include <vector>

namespace tandem {

inline bool shortTests() {
  const char* text = std::getenv("TANDEM_SHORT_TESTS");
  return text != nullptr && std::string_view(text) == "1";
}

// The cases a test runs through: all of them, or only the first when the suite runs shortened.
template <class Case>
std::vector<Case> casesToRun(std::initializer_list<Case> cases) {
  if (shortTests()) return {*cases.begin()};
  return cases;
}

}  // namespace tandem
