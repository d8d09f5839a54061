#include "kernel/attribute.h"

#include <algorithm>

namespace groom {

const char* domain_name(Domain d)
{
    switch (d) {
        case Domain::Point: return "point";
        case Domain::Curve: return "curve";
        case Domain::Detail: return "detail";
    }
    return "?";
}

const char* type_name(AttrType t)
{
    switch (t) {
        case AttrType::Float: return "float";
        case AttrType::Int32: return "int";
        case AttrType::Int64: return "int64";
        case AttrType::Float3: return "float3";
        case AttrType::String: return "string";
    }
    return "?";
}

size_t Attribute::size() const
{
    return std::visit([](const auto& v) { return v.size(); }, data);
}

void Attribute::resize(size_t n)
{
    std::visit([n](auto& v) { v.resize(n); }, data);
}

AttributeData make_attribute_data(AttrType type, size_t size)
{
    switch (type) {
        case AttrType::Float: return std::vector<float>(size);
        case AttrType::Int32: return std::vector<int32_t>(size);
        case AttrType::Int64: return std::vector<int64_t>(size);
        case AttrType::Float3: return std::vector<float3>(size);
        case AttrType::String: return std::vector<std::string>(size);
    }
    return std::vector<float>(size);
}

const Attribute* AttributeSet::find(std::string_view name) const
{
    auto it = std::find_if(attrs_.begin(), attrs_.end(), [&](const Attribute& a) { return a.name == name; });
    return it == attrs_.end() ? nullptr : &*it;
}

Attribute* AttributeSet::find(std::string_view name)
{
    return const_cast<Attribute*>(static_cast<const AttributeSet*>(this)->find(name));
}

Attribute& AttributeSet::add(std::string_view name, Domain domain, AttrType type, size_t size)
{
    if (name.empty()) throw InvalidGeometry("attribute name must not be empty");
    if (type == AttrType::String && domain != Domain::Detail) {
        throw InvalidGeometry("attribute '" + std::string(name) + "': string values are supported on the detail domain only (got " +
                              domain_name(domain) + ")");
    }
    if (Attribute* existing = find(name)) {
        if (existing->type() != type) {
            throw InvalidGeometry("attribute '" + std::string(name) + "' already exists on the " + domain_name(domain) +
                                  " domain as " + type_name(existing->type()) + " (asked for " + type_name(type) + ")");
        }
        return *existing;
    }
    attrs_.push_back(Attribute{std::string(name), domain, make_attribute_data(type, size)});
    return attrs_.back();
}

bool AttributeSet::remove(std::string_view name)
{
    auto it = std::find_if(attrs_.begin(), attrs_.end(), [&](const Attribute& a) { return a.name == name; });
    if (it == attrs_.end()) return false;
    attrs_.erase(it);
    return true;
}

void AttributeSet::resize(size_t n)
{
    for (Attribute& a : attrs_) a.resize(n);
}

}  // namespace groom
