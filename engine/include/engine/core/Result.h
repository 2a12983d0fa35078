// Error values for bad data or environment: the caller decides, tools print and exit non-zero.
#pragma once

#include "engine/core/Check.h"

#include <optional>
#include <string>
#include <utility>

namespace core {

/** A failure that names the function, the file and the element, e.g.
 *  "asset::loadGltf(): Fox.glb: skin 0: joint 7 references node 91, file has 40 nodes". */
struct Error {
    std::string message;
};

/** Either a value or an Error. Reading the value of a failed Result is API misuse (aborts). */
template <class T> class [[nodiscard]] Result {
public:
    Result(T value) : mValue(std::move(value)) {}
    Result(Error error) : mError(std::move(error)) {}

    bool ok() const { return mValue.has_value(); }
    explicit operator bool() const { return ok(); }

    T& value() & {
        ENGINE_CHECK(ok(), mError.message);
        return *mValue;
    }
    const T& value() const& {
        ENGINE_CHECK(ok(), mError.message);
        return *mValue;
    }
    T&& value() && {
        ENGINE_CHECK(ok(), mError.message);
        return std::move(*mValue);
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }

    const Error& error() const {
        ENGINE_CHECK(!ok(), "Result::error() called on a success");
        return mError;
    }

private:
    std::optional<T> mValue;
    Error mError;
};

/** Result of an operation that yields nothing on success. */
class [[nodiscard]] Status {
public:
    Status() = default;
    Status(Error error) : mError(std::move(error)), mFailed(true) {}
    bool ok() const { return !mFailed; }
    explicit operator bool() const { return ok(); }
    const Error& error() const {
        ENGINE_CHECK(mFailed, "Status::error() called on a success");
        return mError;
    }

private:
    Error mError;
    bool mFailed = false;
};

} // namespace core
