// bullet_file_check.cpp — the bounds-checked walk over a `.bullet` file: 12-byte header
// ("BULLET", f|d, -|_ pointer size, v|V endianness, three version digits), then chunks
// {code, len, old pointer, dna_nr, nr} + len bytes, up to the "DNA1" chunk that holds the SDNA
// tables (NAME, TYPE, TLEN, STRC), the layout Bullet's btDefaultSerializer writes.
#include "compare/bullet_file_check.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace btgpu::compare {
namespace {

constexpr size_t kHeaderBytes = 12;

class Reader {
public:
    Reader(const std::vector<char>& b, bool swap) : m_b(b), m_swap(swap) {}
    bool has(size_t at, size_t n) const { return at <= m_b.size() && n <= m_b.size() - at; }
    int32_t i32(size_t at) const
    {
        uint32_t v;
        std::memcpy(&v, m_b.data() + at, 4);
        if (m_swap) v = (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
        return int32_t(v);
    }
    int16_t i16(size_t at) const
    {
        uint16_t v;
        std::memcpy(&v, m_b.data() + at, 2);
        if (m_swap) v = uint16_t((v >> 8) | (v << 8));
        return int16_t(v);
    }
    bool tag(size_t at, const char* t) const { return has(at, 4) && std::memcmp(m_b.data() + at, t, 4) == 0; }

private:
    const std::vector<char>& m_b;
    bool m_swap;
};

struct Dna {
    int names = 0;
    std::vector<int16_t> typeLengths;  // bytes, per type
    std::vector<int16_t> structType;   // type index of each struct
};

// Walks `count` NUL-terminated strings from `at`; false when one runs past `end`.
bool skipStrings(const std::vector<char>& b, size_t& at, size_t end, int count)
{
    for (int i = 0; i < count; ++i) {
        const void* nul = at < end ? std::memchr(b.data() + at, 0, end - at) : nullptr;
        if (!nul) return false;
        at = size_t(static_cast<const char*>(nul) - b.data()) + 1;
    }
    return true;
}

size_t align4(size_t at) { return (at + 3) & ~size_t(3); }

// The SDNA tables inside the DNA chunk [at, end); the loader aligns to 4 from the buffer start.
std::string readDna(const std::vector<char>& b, const Reader& r, size_t at, size_t end, Dna& dna)
{
    auto fault = [&](const std::string& what, size_t where) {
        return "corrupt DNA (" + what + "), at byte " + std::to_string(where);
    };
    if (!r.tag(at, "SDNA") || !r.tag(at + 4, "NAME")) return fault("no SDNA/NAME tag", at);
    at += 8;
    if (!r.has(at, 4) || at + 4 > end) return fault("name count cut off", at);
    dna.names = r.i32(at);
    at += 4;
    if (dna.names <= 0 || size_t(dna.names) > end - at) return fault("name count " + std::to_string(dna.names), at - 4);
    if (!skipStrings(b, at, end, dna.names)) return fault("a name runs past the chunk", at);
    at = align4(at);
    if (at + 8 > end || !r.tag(at, "TYPE")) return fault("no TYPE tag", at);
    const int types = r.i32(at + 4);
    at += 8;
    if (types <= 0 || size_t(types) > end - at) return fault("type count " + std::to_string(types), at - 4);
    if (!skipStrings(b, at, end, types)) return fault("a type name runs past the chunk", at);
    at = align4(at);
    if (at + 4 > end || !r.tag(at, "TLEN")) return fault("no TLEN tag", at);
    at += 4;
    if (size_t(types) * 2 > end - at) return fault("type lengths cut off", at);
    for (int i = 0; i < types; ++i, at += 2) {
        const int16_t len = r.i16(at);
        if (len < 0) return fault("negative type length", at);
        dna.typeLengths.push_back(len);
    }
    if (types & 1) at += 2;
    if (at + 8 > end || !r.tag(at, "STRC")) return fault("no STRC tag", at);
    const int structs = r.i32(at + 4);
    at += 8;
    if (structs <= 0 || size_t(structs) * 4 > end - at) return fault("struct count " + std::to_string(structs), at - 4);
    for (int s = 0; s < structs; ++s) {
        if (at + 4 > end) return fault("struct " + std::to_string(s) + " cut off", at);
        const int16_t type = r.i16(at), fields = r.i16(at + 2);
        if (type < 0 || type >= types) return fault("struct " + std::to_string(s) + " has type " + std::to_string(type), at);
        if (fields < 0 || size_t(fields) * 4 > end - at - 4)
            return fault("struct " + std::to_string(s) + " has " + std::to_string(fields) + " fields", at);
        at += 4;
        for (int f = 0; f < fields; ++f, at += 4) {
            const int16_t ft = r.i16(at), fn = r.i16(at + 2);
            if (ft < 0 || ft >= types || fn < 0 || fn >= dna.names)
                return fault("struct " + std::to_string(s) + " field " + std::to_string(f) + " out of range", at);
        }
        dna.structType.push_back(type);
    }
    return "";
}

FileCheck fail(FileCheck c, const std::string& name, const std::string& what)
{
    c.ok = false;
    c.error = name + ": " + what;
    c.bytes.clear();
    return c;
}

}  // namespace

FileCheck checkBulletBytes(std::vector<char> bytes, const std::string& name)
{
    FileCheck c;
    const std::vector<char>& b = bytes;
    if (b.empty()) return fail(c, name, "empty file, not a .bullet file");
    if (b.size() < kHeaderBytes || std::memcmp(b.data(), "BULLET", 6) != 0)
        return fail(c, name, "not a .bullet file (no \"BULLET\" header; Bullet's btDefaultSerializer writes one)");
    if ((b[6] != 'f' && b[6] != 'd') || (b[7] != '-' && b[7] != '_') || (b[8] != 'v' && b[8] != 'V'))
        return fail(c, name, "not a .bullet file (header \"" + std::string(b.data(), 9) + "\" has no precision, pointer size or endianness)");
    for (int i = 9; i < 12; ++i)
        if (b[size_t(i)] < '0' || b[size_t(i)] > '9') return fail(c, name, "not a .bullet file (no version digits in the header)");
    c.doublePrecision = b[6] == 'd';
    c.pointers64 = b[7] == '-';
    c.bigEndian = b[8] == 'V';
    c.version = (b[9] - '0') * 100 + (b[10] - '0') * 10 + (b[11] - '0');
    const uint32_t one = 1;
    const bool hostLittle = *reinterpret_cast<const unsigned char*>(&one) == 1;
    const Reader r(b, c.bigEndian == hostLittle);
    const size_t chunkHeader = c.pointers64 ? 24 : 20;
    const size_t lenAt = 4, dnaAt = c.pointers64 ? 16 : 12;

    // Bullet's loader takes the first "DNA1" in the file as the DNA chunk, wherever it is.
    size_t firstDna = b.size();
    for (size_t i = kHeaderBytes; i + 4 <= b.size(); ++i)
        if (std::memcmp(b.data() + i, "DNA1", 4) == 0) {
            firstDna = i;
            break;
        }
    if (firstDna == b.size()) return fail(c, name, "truncated or corrupt: no DNA chunk (Bullet writes it last, so the file is cut short)");

    struct Pending {
        size_t at;
        int32_t dnaNr, nr, len;
    };
    std::vector<Pending> data;
    size_t at = kHeaderBytes;
    for (;;) {
        if (!r.has(at, chunkHeader))
            return fail(c, name, "truncated: a chunk header at byte " + std::to_string(at) + " is cut off (file is " +
                                     std::to_string(b.size()) + " bytes)");
        const int32_t len = r.i32(at + lenAt);
        if (len < 0) return fail(c, name, "corrupt: chunk at byte " + std::to_string(at) + " has length " + std::to_string(len));
        if (!r.has(at + chunkHeader, size_t(len)))
            return fail(c, name, "truncated: the chunk at byte " + std::to_string(at) + " needs " + std::to_string(len) +
                                     " bytes, the file ends " + std::to_string(b.size() - at - chunkHeader) + " bytes after its header");
        if (r.tag(at, "DNA1")) break;
        if (at <= firstDna && firstDna < at + chunkHeader + size_t(len) && at != firstDna)
            return fail(c, name, "corrupt: \"DNA1\" inside the chunk at byte " + std::to_string(at));
        if (r.tag(at, "ENDB")) return fail(c, name, "corrupt: end marker before the DNA chunk, at byte " + std::to_string(at));
        data.push_back({at, r.i32(at + dnaAt), r.i32(at + dnaAt + 4), len});
        at += chunkHeader + size_t(len);
    }
    if (at != firstDna) return fail(c, name, "corrupt: \"DNA1\" at byte " + std::to_string(firstDna) + " is not a chunk");
    const size_t dnaStart = at + chunkHeader, dnaEnd = dnaStart + size_t(r.i32(at + lenAt));
    Dna dna;
    const std::string dnaError = readDna(b, r, dnaStart, dnaEnd, dna);
    if (!dnaError.empty()) return fail(c, name, dnaError);
    for (const Pending& p : data) {
        if (p.dnaNr < 0) continue;  // raw bytes (names, arrays): the loader keeps them as they are
        if (size_t(p.dnaNr) >= dna.structType.size())
            return fail(c, name, "corrupt: chunk at byte " + std::to_string(p.at) + " names struct " + std::to_string(p.dnaNr) +
                                     " of " + std::to_string(dna.structType.size()));
        const int64_t need = int64_t(p.nr) * dna.typeLengths[size_t(dna.structType[size_t(p.dnaNr)])];
        if (p.nr < 0 || need > p.len)
            return fail(c, name, "corrupt: chunk at byte " + std::to_string(p.at) + " holds " + std::to_string(p.nr) +
                                     " structs of " + std::to_string(dna.typeLengths[size_t(dna.structType[size_t(p.dnaNr)])]) +
                                     " bytes in " + std::to_string(p.len));
    }
    c.chunks = int(data.size());
    c.ok = true;
    c.bytes = std::move(bytes);
    return c;
}

FileCheck checkBulletFile(const std::string& path)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        FileCheck c;
        return fail(c, path, errno == ENOENT ? "no such file" : std::string("cannot read: ") + std::strerror(errno));
    }
    if (!S_ISREG(st.st_mode)) return fail(FileCheck(), path, "not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(FileCheck(), path, std::string("cannot open: ") + std::strerror(errno));
    std::vector<char> bytes(size_t(st.st_size));
    if (!bytes.empty() && !in.read(bytes.data(), std::streamsize(bytes.size())))
        return fail(FileCheck(), path, "cannot read all " + std::to_string(bytes.size()) + " bytes");
    return checkBulletBytes(std::move(bytes), path);
}

}  // namespace btgpu::compare
