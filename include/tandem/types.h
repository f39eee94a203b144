// Basic types shared by Tandem's public headers: vectors, errors, results.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

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

// A value or an Error. Small on purpose: C++20 has no std::expected.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : m_state(std::move(value)) {}      // NOLINT: implicit on purpose
  Result(Error error) : m_state(std::move(error)) {}  // NOLINT: implicit on purpose

  bool ok() const { return std::holds_alternative<T>(m_state); }
  explicit operator bool() const { return ok(); }
  const std::string& message() const { return std::get<Error>(m_state).message; }
  Status status() const { return ok() ? Status{} : Status{std::get<Error>(m_state)}; }

  T& value() & { return std::get<T>(m_state); }
  const T& value() const& { return std::get<T>(m_state); }
  T&& value() && { return std::get<T>(std::move(m_state)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Error> m_state;
};

inline bool isFinite(const Vec3& v) { return v.allFinite(); }

}  // namespace tandem
