// The memory one command may use: ops estimate what they are about to allocate and compare it with
// this budget before allocating, so a parameter that asks for too much is refused with the option
// to change and the estimate, instead of the process being killed (or, worse, a machine swapping).
// One process-wide value, like the thread limit (kernel/parallel.h): the CLI sets it from --memory
// (or GROOM_MEMORY) for the command it runs.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace groom {

/// Bytes one command may use: the value of the innermost live MemoryLimit, else
/// default_memory_budget().
uint64_t memory_budget();

/// Half the memory this process can have (at least 1 GiB): the machine's physical memory, or the
/// container's (cgroup memory.max) when smaller, halved to leave room beside the system and another
/// program; and at most 3/4 of `ulimit -v` / `ulimit -d` when those are set, so a job the process
/// could not allocate is refused up front.
uint64_t default_memory_budget();

/// Sets memory_budget() for the lifetime of the object (the CLI's --memory); 0 keeps the current one.
class MemoryLimit {
public:
    explicit MemoryLimit(uint64_t bytes);
    ~MemoryLimit();
    MemoryLimit(const MemoryLimit&) = delete;
    MemoryLimit& operator=(const MemoryLimit&) = delete;

private:
    uint64_t previous_;
};

/// Says, for the lifetime of the object, which large allocation is under way and what it was
/// estimated to need ("scalp: the level set at `voxel` 0.004, estimated 4.75 GiB; use a larger
/// `voxel`"). An allocation failure that cannot be caught where it happens (OpenVDB's trees allocate
/// while they are destroyed, so a bad_alloc inside meshToVolume ends in std::terminate) is then
/// still reported with the option to change. Process-wide, not per thread: the failure may be on
/// any worker.
class MemoryNote {
public:
    explicit MemoryNote(std::string text);
    ~MemoryNote();
    MemoryNote(const MemoryNote&) = delete;
    MemoryNote& operator=(const MemoryNote&) = delete;

private:
    std::string previous_;
    int uncaught_ = 0;
};

/// The innermost live MemoryNote's text; else the text of the last one destroyed by an exception
/// passing through it (so a handler above can still say what failed); else "". Also "" when another
/// thread is changing it: safe to call from a terminate handler.
std::string memory_note();

/// What this process holds in memory now (resident set, /proc/self/statm), or 0 where that cannot
/// be read. Estimates add it to what they are about to allocate: a command's peak is what it
/// already holds (libraries, inputs) plus the new allocation, and at the sizes of a default scalp
/// the first is the larger part.
uint64_t resident_bytes();

/// "12.5 GiB", "300 MiB": a byte count as messages show it.
std::string format_bytes(double bytes);

/// Throws LimitExceeded when `bytes` (an estimate; may be inf) is over memory_budget():
/// "<what> needs about <bytes>, over the <budget> memory budget; <advice> (or raise the budget with
/// `memory`)". `what` says what is being made and from which option ("resample: 1e+10 points from
/// `segment_length` 0.1"); `advice` names the option to change.
void check_memory(const std::string& what, double bytes, std::string_view advice);

/// Bytes of one point (or curve) of every column of `curves`' point (or curve) domain: what a copy
/// of that domain costs per element. Declared here so ops need not know the attribute layout.
class CurveSet;
double bytes_per_point(const CurveSet& curves);
double bytes_per_curve(const CurveSet& curves);

}  // namespace groom
