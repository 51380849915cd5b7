// SPDX-License-Identifier: MIT
// Result<T> and Status carry errors from anything that reads the outside world (files, JSON, meshes).
// Shaped like std::expected so the engine can switch at C++23; no exception crosses the public API.
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace supermodal
{

/// What went wrong and where: `where` is a JSON pointer or `file:line`, `what` says found vs expected.
struct Error {
    std::string file;  ///< Source file, or empty.
    std::string where; ///< JSON pointer ("/bodies/3/shape/exponents/0") or other locator, may be empty.
    std::string what;  ///< "expected a number > 0, found -1".

    /// "file: where: what", leaving out empty parts.
    [[nodiscard]] std::string message() const
    {
        std::string out;
        if (!file.empty())
            out += file + ": ";
        if (!where.empty())
            out += where + ": ";
        return out + what;
    }
};

/// A value or an Error.
template <class T> class [[nodiscard]] Result
{
  public:
    Result(T value) : m_value(std::move(value)) {}
    Result(Error error) : m_error(std::move(error)) {}

    [[nodiscard]] bool has_value() const { return m_value.has_value(); }
    explicit operator bool() const { return has_value(); }
    [[nodiscard]] T& value()
    {
        assert(has_value());
        return *m_value;
    }
    [[nodiscard]] const T& value() const
    {
        assert(has_value());
        return *m_value;
    }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    [[nodiscard]] const Error& error() const { return m_error; }

  private:
    std::optional<T> m_value;
    Error m_error;
};

/// Success, or an Error.
class [[nodiscard]] Status
{
  public:
    Status() = default;
    Status(Error error) : m_error(std::move(error)), m_ok(false) {}

    [[nodiscard]] bool ok() const { return m_ok; }
    explicit operator bool() const { return m_ok; }
    [[nodiscard]] const Error& error() const { return m_error; }

  private:
    Error m_error;
    bool m_ok = true;
};

} // namespace supermodal
