#include "kernel/io/memory_files.h"

#include "kernel/error.h"

#include <map>
#include <mutex>

namespace groom {

namespace {

struct Store {
    std::mutex mutex;
    std::map<std::string, CurveSet, std::less<>> files;
};

Store& store()
{
    static Store s;
    return s;
}

}  // namespace

bool is_memory_path(std::string_view path) { return path.substr(0, 4) == "mem:"; }

void store_memory_curves(const std::string& path, CurveSet curves)
{
    Store& s = store();
    const std::lock_guard lock(s.mutex);
    s.files.insert_or_assign(path, std::move(curves));
}

CurveSet read_memory_curves(const std::string& path)
{
    Store& s = store();
    const std::lock_guard lock(s.mutex);
    const auto it = s.files.find(path);
    if (it == s.files.end()) throw IoError(path + ": no curves stored under this name");
    return it->second;
}

CurveSet take_memory_curves(const std::string& path)
{
    Store& s = store();
    const std::lock_guard lock(s.mutex);
    const auto it = s.files.find(path);
    if (it == s.files.end()) throw IoError(path + ": no curves stored under this name");
    CurveSet out = std::move(it->second);
    s.files.erase(it);
    return out;
}

void erase_memory_curves(const std::string& path)
{
    Store& s = store();
    const std::lock_guard lock(s.mutex);
    s.files.erase(path);
}

}  // namespace groom
