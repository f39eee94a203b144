// Basic types shared by Tandem's public headers: vectors, errors, results.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <variant>

namespace tandem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// What went wrong, in words a user can act on ("cloth grid: columns must be >= 2, got 1").
struct Error {
  std::string message;
};

// The outcome of an operation that returns nothing: ok, or an Error.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : m_error(std::move(error.message)), m_failed(true) {}  // NOLINT: implicit on purpose

  bool ok() const { return !m_failed; }
  explicit operator bool() const { return ok(); }
  const std::string& message() const { return m_error; }

 private:
  std::string m_error;
  bool m_failed = false;
};

namespace detail {
// Using a Result that holds an error as its value is a programmer error: say which error, stop.
[[noreturn]] inline void usedErrorAsValue(const std::string& message) {
  std::fprintf(stderr, "tandem: a Result holding an error was used as its value: %s\n", message.c_str());
  std::abort();
}
}  // namespace detail

// A value or an Error. Small on purpose: C++20 has no std::expected. Check ok() (or the bool)
// before using the value: using an error as a value stops the program with the error's message.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : m_state(std::move(value)) {}      // NOLINT: implicit on purpose
  Result(Error error) : m_state(std::move(error)) {}  // NOLINT: implicit on purpose

  bool ok() const { return std::holds_alternative<T>(m_state); }
  explicit operator bool() const { return ok(); }
  // The error's message; empty when ok.
  const std::string& message() const {
    static const std::string none;
    return ok() ? none : std::get<Error>(m_state).message;
  }
  Status status() const { return ok() ? Status{} : Status{std::get<Error>(m_state)}; }

  T& value() & { return *checkedValue(); }
  const T& value() const& { return *const_cast<Result*>(this)->checkedValue(); }
  T&& value() && { return std::move(*checkedValue()); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  T* checkedValue() {
    T* value = std::get_if<T>(&m_state);
    if (!value) detail::usedErrorAsValue(std::get<Error>(m_state).message);
    return value;
  }

  std::variant<T, Error> m_state;
};

inline bool isFinite(const Vec3& v) { return v.allFinite(); }

}  // namespace tandem
