// Numbers in error messages, as a user would write them ("-0.5", "nan", "1e+07").
#pragma once

#include <cstdio>
#include <string>

namespace tandem {

inline std::string formatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

}  // namespace tandem
