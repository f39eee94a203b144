// Reading JSON objects field by field, with the JSON path of every value at hand: a wrong type,
// a value out of range or a field nobody reads is reported as "/path/to/field: what is wrong".
#pragma once

#include <tandem/types.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tandem::scene {

using Json = nlohmann::json;

// Thrown inside the reader only; loadScene turns it into an Error.
struct ReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& path, const std::string& problem) {
  throw ReadError(path + ": " + problem);
}

inline std::string typeName(const Json& value) {
  if (value.is_number_integer() || value.is_number_unsigned()) return "an integer";
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "a boolean";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "null";
}

inline std::string formatValue(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

inline double readNumber(const Json& value, const std::string& path) {
  if (!value.is_number()) fail(path, "must be a number, got " + typeName(value));
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail(path, "must be finite");
  return number;
}

inline Vec3 readVec3(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3) fail(path, "must be an array of 3 numbers");
  return {readNumber(value[0], path + "/0"), readNumber(value[1], path + "/1"), readNumber(value[2], path + "/2")};
}

inline int readInteger(const Json& value, const std::string& path) {
  if (!value.is_number_integer() && !value.is_number_unsigned())
    fail(path, "must be an integer, got " + typeName(value));
  const long long number = value.get<long long>();
  if (number < -2147483647LL || number > 2147483647LL) fail(path, "is out of range");
  return static_cast<int>(number);
}

// One JSON object being read. Every field asked for (present or not) is remembered; finish()
// refuses the fields nobody asked for, so a misspelt field is an error, not silently ignored.
class ObjectReader {
 public:
  ObjectReader(const Json& value, std::string path) : m_value(value), m_path(std::move(path)) {
    if (!m_value.is_object()) fail(pathOrRoot(), "must be an object, got " + typeName(m_value));
  }

  const std::string& path() const { return m_path; }
  std::string fieldPath(const std::string& key) const { return m_path + "/" + key; }

  bool has(const std::string& key) {
    m_known.insert(key);
    return m_value.contains(key);
  }
  const Json& required(const std::string& key) {
    if (!has(key)) fail(pathOrRoot(), "missing field '" + key + "'");
    return m_value.at(key);
  }

  double number(const std::string& key, double fallback) { return has(key) ? number(key) : fallback; }
  double number(const std::string& key) { return readNumber(required(key), fieldPath(key)); }
  // A number in [low, high] (or (low, high] when lowOpen).
  double numberIn(const std::string& key, double fallback, double low, double high, bool lowOpen = false) {
    if (!has(key)) return fallback;
    const double value = number(key);
    if (value < low || value > high || (lowOpen && value == low))
      fail(fieldPath(key), std::string("must be in ") + (lowOpen ? "(" : "[") + formatValue(low) + ", " +
                               formatValue(high) + "], got " + formatValue(value));
    return value;
  }
  double positive(const std::string& key, double fallback) {
    if (!has(key)) return fallback;
    const double value = number(key);
    if (!(value > 0)) fail(fieldPath(key), "must be > 0, got " + formatValue(value));
    return value;
  }
  double nonNegative(const std::string& key, double fallback) {
    if (!has(key)) return fallback;
    const double value = number(key);
    if (!(value >= 0)) fail(fieldPath(key), "must be >= 0, got " + formatValue(value));
    return value;
  }
  int integer(const std::string& key, int fallback, int low, int high) {
    if (!has(key)) return fallback;
    const int value = readInteger(m_value.at(key), fieldPath(key));
    if (value < low || value > high)
      fail(fieldPath(key), "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                               std::to_string(value));
    return value;
  }
  // A 32-bit mask: an integer in [0, 2³² − 1].
  uint32_t bits(const std::string& key, uint32_t fallback) {
    if (!has(key)) return fallback;
    const Json& value = m_value.at(key);
    const bool fits = value.is_number_unsigned() ? value.get<uint64_t>() <= 0xFFFFFFFFull
                                                 : value.is_number_integer() && value.get<int64_t>() >= 0 &&
                                                       value.get<int64_t>() <= 0xFFFFFFFFll;
    if (!fits) fail(fieldPath(key), "must be an integer in [0, 4294967295] (a 32-bit mask), got " + value.dump());
    return static_cast<uint32_t>(value.get<uint64_t>());
  }
  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const Json& value = m_value.at(key);
    if (!value.is_boolean()) fail(fieldPath(key), "must be true or false, got " + typeName(value));
    return value.get<bool>();
  }
  std::string string(const std::string& key, const std::string& fallback) {
    return has(key) ? string(key) : fallback;
  }
  std::string string(const std::string& key) {
    const Json& value = required(key);
    if (!value.is_string()) fail(fieldPath(key), "must be a string, got " + typeName(value));
    return value.get<std::string>();
  }
  Vec3 vec3(const std::string& key, const Vec3& fallback) { return has(key) ? vec3(key) : fallback; }
  Vec3 vec3(const std::string& key) { return readVec3(required(key), fieldPath(key)); }

  // A colour: [r, g, b] with each in [0, 1], or "#rrggbb".
  std::array<double, 3> colour(const std::string& key) {
    const Json& value = required(key);
    const std::string path = fieldPath(key);
    const std::string expected = "must be [r, g, b] with each in [0, 1], or \"#rrggbb\"";
    std::array<double, 3> rgb{};
    if (value.is_string()) {
      const std::string text = value.get<std::string>();
      const bool hex = text.size() == 7 && text[0] == '#' &&
                       text.find_first_not_of("0123456789abcdefABCDEF", 1) == std::string::npos;
      if (!hex) fail(path, expected + ", got \"" + text + "\"");
      for (int k = 0; k < 3; ++k) rgb[k] = std::stoi(text.substr(1 + 2 * k, 2), nullptr, 16) / 255.0;
      return rgb;
    }
    if (!value.is_array() || value.size() != 3) fail(path, expected + ", got " + typeName(value));
    for (int k = 0; k < 3; ++k) {
      rgb[k] = readNumber(value[k], path + "/" + std::to_string(k));
      if (rgb[k] < 0 || rgb[k] > 1) fail(path + "/" + std::to_string(k), "must be in [0, 1], got " + formatValue(rgb[k]));
    }
    return rgb;
  }

  // A string that must be one of `choices` (name, value).
  template <class T>
  T choice(const std::string& key, const std::vector<std::pair<std::string, T>>& choices, T fallback) {
    if (!has(key)) return fallback;
    const std::string value = string(key);
    std::string allowed;
    for (const auto& [name, result] : choices) {
      if (name == value) return result;
      allowed += (allowed.empty() ? "" : ", ") + name;
    }
    fail(fieldPath(key), "unknown value '" + value + "' (expected one of: " + allowed + ")");
  }

  // Fails on the first field never asked for.
  void finish() const {
    for (auto it = m_value.begin(); it != m_value.end(); ++it)
      if (!m_known.count(it.key())) {
        std::string known;
        for (const std::string& key : m_known) known += (known.empty() ? "" : ", ") + key;
        fail(fieldPath(it.key()), "unknown field '" + it.key() + "' (known here: " + known + ")");
      }
  }

 private:
  std::string pathOrRoot() const { return m_path.empty() ? "/" : m_path; }

  const Json& m_value;
  std::string m_path;
  std::set<std::string> m_known;
};

}  // namespace tandem::scene
