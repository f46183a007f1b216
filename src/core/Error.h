#pragma once
// Error values for input problems (files, settings, flags, shaders). Invariants use BOUNCE_CHECK
// instead (Check.h). A message names what is wrong and where: "scene.json:12: light 'key': ...".
#include <fmt/format.h>

#include <string>
#include <utility>
#include <variant>

namespace bounce {

struct Error {
    std::string message;
};

template <class... Args>
Error makeError(fmt::format_string<Args...> format, Args&&... args) {
    return Error{fmt::format(format, std::forward<Args>(args)...)};
}

// A value or an Error. C++23's std::expected is not available under C++20; this is the subset used.
template <class T>
class [[nodiscard]] Expected {
public:
    Expected(T value) : m_v(std::in_place_index<0>, std::move(value)) {}
    Expected(Error error) : m_v(std::in_place_index<1>, std::move(error)) {}

    bool ok() const noexcept { return m_v.index() == 0; }
    explicit operator bool() const noexcept { return ok(); }

    T& value() & { return std::get<0>(m_v); }
    const T& value() const& { return std::get<0>(m_v); }
    T&& value() && { return std::get<0>(std::move(m_v)); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    const Error& error() const { return std::get<1>(m_v); }

private:
    std::variant<T, Error> m_v;
};

template <>
class [[nodiscard]] Expected<void> {
public:
    Expected() = default;
    Expected(Error error) : m_error(std::move(error)), m_ok(false) {}
    bool ok() const noexcept { return m_ok; }
    explicit operator bool() const noexcept { return m_ok; }
    const Error& error() const { return m_error; }

private:
    Error m_error;
    bool m_ok = true;
};

// Propagates an error: BOUNCE_TRY(auto x, f()); or BOUNCE_TRY_VOID(g());
#define BOUNCE_CONCAT_INNER(a, b) a##b
#define BOUNCE_CONCAT(a, b) BOUNCE_CONCAT_INNER(a, b)
#define BOUNCE_TRY_IMPL(tmp, decl, expr) \
    auto tmp = (expr);                   \
    if (!tmp.ok()) return tmp.error();   \
    decl = std::move(tmp).value()
#define BOUNCE_TRY(decl, expr) BOUNCE_TRY_IMPL(BOUNCE_CONCAT(bounceTry_, __LINE__), decl, expr)
#define BOUNCE_TRY_VOID(expr)                         \
    do {                                              \
        auto bounceTryV_ = (expr);                    \
        if (!bounceTryV_.ok()) return bounceTryV_.error(); \
    } while (0)

}  // namespace bounce
