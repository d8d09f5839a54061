#include "kernel/memory_budget.h"

#include "kernel/curve_set.h"
#include "kernel/error.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>

namespace groom {

namespace {
// 0 = not set: default_memory_budget().
std::atomic<uint64_t> g_budget{0};

size_t bytes_of(AttrType t)
{
    switch (t) {
        case AttrType::Float: return sizeof(float);
        case AttrType::Int32: return sizeof(int32_t);
        case AttrType::Int64: return sizeof(int64_t);
        case AttrType::Float3: return sizeof(float3);
        case AttrType::String: return sizeof(std::string);
    }
    return 8;
}

double domain_bytes(const CurveSet& curves, Domain d)
{
    double b = 0.0;
    for (const Attribute& a : curves.attributes(d).all()) b += double(bytes_of(a.type()));
    return b;
}
}  // namespace

namespace {
std::mutex g_note_mutex;
std::string g_note, g_unwound_note;
}  // namespace

uint64_t default_memory_budget()
{
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    uint64_t memory = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : (8ull << 30);
    // cgroup v2: "max" or a byte count.
    if (std::FILE* f = std::fopen("/sys/fs/cgroup/memory.max", "r")) {
        unsigned long long limit = 0;
        if (std::fscanf(f, "%llu", &limit) == 1 && limit > 0) memory = std::min<uint64_t>(memory, limit);
        std::fclose(f);
    }
    uint64_t budget = std::max<uint64_t>(memory / 2, 1ull << 30);
    for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
        rlimit rl{};
        if (::getrlimit(resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) budget = std::min<uint64_t>(budget, rl.rlim_cur / 4 * 3);
    }
    return std::max<uint64_t>(budget, 64ull << 20);
}


MemoryNote::MemoryNote(std::string text) : uncaught_(std::uncaught_exceptions())
{
    const std::lock_guard lock(g_note_mutex);
    previous_ = std::move(g_note);
    g_note = std::move(text);
    g_unwound_note.clear();
}

MemoryNote::~MemoryNote()
{
    const std::lock_guard lock(g_note_mutex);
    if (std::uncaught_exceptions() > uncaught_) g_unwound_note = g_note;
    g_note = std::move(previous_);
}

std::string memory_note()
{
    std::unique_lock lock(g_note_mutex, std::try_to_lock);
    if (!lock) return {};
    return g_note.empty() ? g_unwound_note : g_note;
}

uint64_t memory_budget()
{
    const uint64_t b = g_budget.load(std::memory_order_relaxed);
    return b ? b : default_memory_budget();
}

MemoryLimit::MemoryLimit(uint64_t bytes) : previous_(g_budget.load())
{
    if (bytes) g_budget.store(bytes);
    const std::lock_guard lock(g_note_mutex);
    g_unwound_note.clear();  // a new command: an earlier one's failure is not this one's
}

MemoryLimit::~MemoryLimit()
{
    g_budget.store(previous_);
}

uint64_t resident_bytes()
{
    uint64_t bytes = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
        unsigned long long size = 0, resident = 0;
        if (std::fscanf(f, "%llu %llu", &size, &resident) == 2) bytes = uint64_t(resident) * uint64_t(::sysconf(_SC_PAGESIZE));
        std::fclose(f);
    }
    return bytes;
}

std::string format_bytes(double bytes)
{
    char buf[48];
    if (!(bytes < 1e30)) return "more than 1e30 bytes";
    if (bytes >= double(1ull << 30)) std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / double(1ull << 30));
    else if (bytes >= double(1ull << 20)) std::snprintf(buf, sizeof buf, "%.3g MiB", bytes / double(1ull << 20));
    else std::snprintf(buf, sizeof buf, "%.0f bytes", bytes);
    return buf;
}

void check_memory(const std::string& what, double bytes, std::string_view advice)
{
    const uint64_t budget = memory_budget();
    if (bytes <= double(budget)) return;
    throw LimitExceeded(what + (std::isfinite(bytes) ? " needs about " + format_bytes(bytes) : std::string(" needs unbounded memory")) +
                        ", over the " + format_bytes(double(budget)) +
                        " memory budget; " + std::string(advice) + " (or raise the budget with `memory` GiB)");
}

double bytes_per_point(const CurveSet& curves)
{
    return domain_bytes(curves, Domain::Point);
}

double bytes_per_curve(const CurveSet& curves)
{
    return domain_bytes(curves, Domain::Curve) + sizeof(int64_t);  // + the offset
}

}  // namespace groom
