// Private to the gl module: the checks, in debug and test builds, that every storage block a draw
// or dispatch reads sits at its registered binding and holds the buffer bound there for it, and
// that no dispatch follows a mipmap generation without a finish or barrier between.
#pragma once

#include "engine/gl/Registry.h"

#include <cstdint>
#include <string>

namespace gl::detail {

/** Notes a linked program's storage blocks (their names and bindings), for the check. */
void recordProgram(std::uint32_t id, const std::string& name);
/** Forgets a deleted program (its name may be reused). */
void forgetProgram(std::uint32_t id);
/** Notes that `buffer` was bound at `slot` (bindStorage). */
void recordStorage(const StorageSlot& slot, std::uint32_t buffer);
/** Checks the current program before a draw or dispatch; a mismatch is logged and counted as a
 *  GL error. */
void checkBindings(const char* command);
/** Notes a glGenerateMipmap: llvmpipe's rasteriser makes the levels later, on its own threads,
 *  and its compute dispatches do not wait for it (docs/hardening.md, "Deterministic frames"). */
void recordMipmaps();
/** Notes a finish or a memory barrier: work issued before it is done for what follows. */
void recordSynchronised();
/** checkBindings, and that no mipmap generation is pending (else an error naming `command`). */
void checkDispatch(const char* command);

} // namespace gl::detail
