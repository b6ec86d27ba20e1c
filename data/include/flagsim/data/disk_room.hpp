#pragma once
// Whether a file may still grow by some bytes: the free space of its disk and
// the process's file-size limit (RLIMIT_FSIZE), whichever is smaller. A run
// checks before each frame, so that it stops with its file whole instead of
// failing half-way through a write.
#include <cstdint>
#include <optional>
#include <string>

namespace flagsim::data {

/// nullopt when `path` (an existing file, or one to be created in an existing
/// directory) can grow by `need_bytes`; otherwise why not, as one sentence:
/// "no room for more frames: 1.2 MB left on the disk or under the file size
/// limit, the next ones need 3.4 MB". A disk whose free space cannot be read
/// counts as unlimited.
std::optional<std::string> no_room_for(const std::string& path, std::uintmax_t need_bytes);

}  // namespace flagsim::data
