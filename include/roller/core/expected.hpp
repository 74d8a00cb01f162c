#pragma once
// A value, or why it could not be computed (std::expected is C++23). What an evaluation at a
// trial point returns: a line search that meets a point the strip cannot take (an inverted
// element) shortens its step on the answer, instead of catching an exception.
#include <optional>
#include <string>
#include <utility>

namespace roller {

struct Unexpected {
  std::string message;
};

template <class T>
class Expected {
 public:
  Expected(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor): a value is an answer
  Expected(Unexpected failure) : error_(std::move(failure.message)) {}  // NOLINT(google-explicit-constructor)
  bool has_value() const { return value_.has_value(); }
  explicit operator bool() const { return has_value(); }
  const T& operator*() const { return *value_; }
  const T* operator->() const { return &*value_; }
  // Why there is no value ("" when there is one).
  const std::string& error() const { return error_; }

 private:
  std::optional<T> value_;
  std::string error_;
};

}  // namespace roller
