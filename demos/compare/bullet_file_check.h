// bullet_file_check.h — checks a `.bullet` file's structure before Bullet's loader sees it.
// Bullet's bFile trusts every length and index in the file (a truncated or corrupt file makes
// it read past its buffer), so the header, every chunk header and the DNA's tables are walked
// here first, bounds-checked, and the first fault is named with its byte offset.
#pragma once
#include <string>
#include <vector>

namespace btgpu::compare {

struct FileCheck {
    bool ok = false;
    std::string error;        // "<path>: <what>, at byte N", when not ok
    std::vector<char> bytes;  // the whole file (what the loader then parses), when ok
    int version = 0;          // Bullet version that wrote it (324 for 3.24)
    bool doublePrecision = false;
    bool pointers64 = false;
    bool bigEndian = false;
    int chunks = 0;           // data chunks before the DNA
};

// Reads and checks `path`: present, a regular readable file, Bullet's header, chunks that fit
// inside the file, a DNA chunk whose name/type/struct tables are complete and in range, and
// data chunks whose struct index and element count the DNA can describe.
FileCheck checkBulletFile(const std::string& path);
// The same on bytes already in memory (`name` is used in the message).
FileCheck checkBulletBytes(std::vector<char> bytes, const std::string& name);

}  // namespace btgpu::compare
