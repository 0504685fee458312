// kernel_inline.cpp — inlines a kernel file's quoted #includes under #line markers; used by
// the build-time embedder and by the BTGPU_KERNEL_DIR development override.
#include "cl/kernel_source.h"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace btgpu::cl {

namespace {

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("btgpu: cannot read kernel file " + path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string dirOf(const std::string& rel)
{
    size_t p = rel.rfind('/');
    return p == std::string::npos ? std::string() : rel.substr(0, p + 1);
}

// Resolves "a/../b" so each header is inlined once whatever path reached it.
std::string normalise(const std::string& path)
{
    std::vector<std::string> parts;
    std::stringstream ss(path);
    std::string item;
    while (std::getline(ss, item, '/')) {
        if (item.empty() || item == ".") continue;
        if (item == ".." && !parts.empty()) parts.pop_back();
        else parts.push_back(item);
    }
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i) out += (i ? "/" : "") + parts[i];
    return out;
}

// A header that says this in its first line is inlined at every include (it is meant to be
// included more than once, with different macros around it: kernels/shared/pgs_edges.h).
const char* const kEveryInclude = "inlined at every include";

void inlineInto(const std::string& dir, const std::string& rel, std::set<std::string>& seen, std::string& out)
{
    const std::string text = readFile(dir + "/" + rel);
    const bool everyTime = text.substr(0, text.find('\n')).find(kEveryInclude) != std::string::npos;
    if (!everyTime && !seen.insert(rel).second) return;
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    out += "#line 1 \"" + rel + "\"\n";
    while (std::getline(in, line)) {
        ++lineNo;
        size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 9, "#include ") == 0) {
            size_t q0 = line.find('"', p);
            size_t q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
            if (q1 != std::string::npos) {
                std::string inc = normalise(dirOf(rel) + line.substr(q0 + 1, q1 - q0 - 1));
                inlineInto(dir, inc, seen, out);
                out += "#line " + std::to_string(lineNo + 1) + " \"" + rel + "\"\n";
                continue;
            }
        }
        out += line + "\n";
    }
}

}  // namespace

std::string inlineKernelFile(const std::string& kernelDir, const std::string& relPath)
{
    std::set<std::string> seen;
    std::string out;
    inlineInto(kernelDir, relPath, seen, out);
    return out;
}

}  // namespace btgpu::cl

