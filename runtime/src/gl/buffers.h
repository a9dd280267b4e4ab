#pragma once
// Immutable-storage buffers (glNamedBufferStorage) of typed elements, never of size 0: a shader
// storage binding needs a buffer even when there is nothing in it.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "gl/gl_object.h"

namespace meadow::runtime::gl {

// Room for `count` elements of T, filled from `data` when it is given (else left undefined).
template <class T>
Buffer bufferFor(std::size_t count, const T* data = nullptr,
                 GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
    Buffer b = Buffer::create();
    glNamedBufferStorage(
        b.id(), static_cast<GLsizeiptr>(std::max<std::size_t>(count, 1) * sizeof(T)), data, flags);
    return b;
}

template <class T>
Buffer bufferOf(const std::vector<T>& data, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
    return bufferFor(data.size(), data.empty() ? nullptr : data.data(), flags);
}

}  // namespace meadow::runtime::gl
