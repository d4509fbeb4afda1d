#pragma once
// Reading a user's input files: meshes, scenarios, sessions and the editor's preferences are
// read through here, and `primo edit --script` checks its file here, so that none of them can
// make PriMo wait for ever or read without end.
// A named pipe, a folder or a device (/dev/zero, /dev/urandom, a terminal) given as a file
// would block the open or never reach its end; a huge file (a 10 GB sparse file) would be
// read until memory runs out. Both are refused before the file is opened, in one line naming
// it. A symbolic link to a regular file is fine.

#include <cstdint>
#include <string>

namespace primo {

// Larger than any input PriMo can use: mesh counts stop at 2^31 - 1, and a 2 GiB OBJ holds
// some 20 million faces, several times what fits in memory once solved (docs/reliability.md).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t(2) << 30;

// Throws primo::Error unless `path` is a regular file (after following links) of at most
// kMaxInputFileBytes: "<path>: not a regular file (a named pipe)", "<path>: cannot open: No
// such file or directory", "<path>: the file is 10737418240 bytes, more than an input may be
// (2 GiB = 2147483648 bytes)".
// The file is opened and closed again, so a file without read permission is named here too.
// For readers that open the file themselves (Assimp); the others use read_input_file.
void check_input_file(const std::string& path);

// The whole file, byte for byte, after check_input_file. Throws primo::Error naming `path` on
// any failure, also when the file was replaced by a special file or grew past the limit since
// it was checked.
std::string read_input_file(const std::string& path);

}  // namespace primo
