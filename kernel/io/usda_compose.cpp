// Composition of one layer (usda_syntax.h compose_curves): what a USD stage would show of this file alone.
// Each prim is the ordered list of the specs that speak for it, strongest first, in LIVRPS order: its
// local specs, then what its inherits bring, then its selected variants' bodies, then its references and
// payloads, then its specializes (each arc's target composed the same way, recursively). A property's
// value is the first spec's that has one; children are the union of every spec's children. This is
// the flattening `usdcat --flatten` does, restricted to arcs inside the file.
//
// Stays linear in the number of prims: a prim with one spec and no arcs costs its children and
// properties only; arc targets are composed once and cached.
#include "kernel/io/usda_syntax.h"

#include "kernel/error.h"

#include <unordered_map>
#include <unordered_set>

namespace groom::io::usda {

namespace {

/// Arcs followed deeper than this are a cycle or a file built to hurt.
constexpr int kMaxArcDepth = 64;
/// Composed prims nest at most this deep (the parser's limit for written ones).
constexpr int kMaxPrimDepth = 1000;
/// Spec entries listed over the whole composition: a real file lists a few per prim.
constexpr size_t kMaxWork = 50'000'000;

class Composer {
public:
    Composer(const Layer& layer, const std::string& file, const std::vector<std::string>& selected, const Warn& warn, std::vector<std::string>& skipped)
        : layer_(layer), file_(file), selected_(selected), matched_(selected.size(), false), warn_(warn), skipped_(skipped)
    {
    }

    std::vector<ComposedCurves> run()
    {
        for (const auto& [name, local] : group_children(layer_.roots)) visit("/" + name, expand(local, "/" + name, 0), kIdentity, false, 0);
        for (size_t i = 0; i < selected_.size(); ++i) {
            if (!matched_[i]) {
                throw InvalidParam(file_ + ": --prim " + selected_[i] + ": no such prim in the file (or it is inactive, an `over` or a `class`)");
            }
        }
        return std::move(out_);
    }

private:
    void say(const std::string& message) const
    {
        if (warn_) warn_(message);
    }

    const PrimSpec& spec(int32_t i) const { return layer_.specs[static_cast<size_t>(i)]; }

    std::string where(size_t line) const { return file_ + ":" + std::to_string(line); }

    /// Children of the given specs grouped by name, in order of first appearance (strongest spec first).
    std::vector<std::pair<std::string, std::vector<int32_t>>> group_children(const std::vector<int32_t>& specs_children) const
    {
        std::vector<std::pair<std::string, std::vector<int32_t>>> groups;
        std::unordered_map<std::string_view, size_t> slot;
        for (int32_t c : specs_children) {
            const auto [it, added] = slot.emplace(spec(c).name, groups.size());
            if (added) groups.push_back({spec(c).name, {}});
            groups[it->second].second.push_back(c);
        }
        return groups;
    }

    /// The full ordered spec list of a prim from its local specs (strongest first).
    std::vector<int32_t> expand(const std::vector<int32_t>& local, const std::string& path, int depth)
    {
        bool arcs = false;
        for (int32_t s : local) {
            const PrimSpec& p = spec(s);
            arcs = arcs || !p.references.empty() || !p.inherits.empty() || !p.specializes.empty() || !p.variant_sets.empty();
        }
        if (!arcs) return local;  // the common case: nothing to compose
        if (depth > kMaxArcDepth) {
            say(where(spec(local.front()).line) + ": <" + path + ">: composition arcs nested deeper than " + std::to_string(kMaxArcDepth) +
                  " (a cycle?); arcs below this depth are not followed");
            return local;
        }
        std::vector<int32_t> inherits, references, specializes;
        for (int32_t s : local)
            for (const Arc& a : spec(s).inherits) add_target(a, inherits, path, depth);
        for (int32_t s : local)
            for (const Arc& a : spec(s).references) add_target(a, references, path, depth);
        for (int32_t s : local)
            for (const Arc& a : spec(s).specializes) add_target(a, specializes, path, depth);

        // Selections: the strongest opinion among every spec that speaks for the prim.
        auto selection = [&](const std::string& set) -> const std::string* {
            for (const std::vector<int32_t>* list : std::initializer_list<const std::vector<int32_t>*>{&local, &inherits, &references, &specializes})
                for (int32_t s : *list)
                    for (const auto& [k, v] : spec(s).variant_selection)
                        if (k == set) return &v;
            return nullptr;
        };
        std::vector<int32_t> variants;
        for (int32_t s : local) {
            for (const VariantSet& vs : spec(s).variant_sets) {
                const std::string* chosen = selection(vs.name);
                if (!chosen || chosen->empty()) {
                    say(where(spec(s).line) + ": variantSet \"" + vs.name + "\" of <" + path +
                          "> has no selection; as in USD, none of its variants is read (select one with `variants = { string " + vs.name +
                          " = \"...\" }`)");
                    continue;
                }
                bool found = false;
                for (const auto& [name, body] : vs.variants) {
                    if (name != *chosen) continue;
                    found = true;
                    const std::vector<int32_t> full = expand({body}, path, depth + 1);
                    variants.insert(variants.end(), full.begin(), full.end());
                }
                if (!found) say(where(spec(s).line) + ": variantSet \"" + vs.name + "\" of <" + path + "> has no variant \"" + *chosen + "\" (the one selected); none read");
            }
        }
        // A spec reached twice (two arcs to one prim, diamonds) speaks once, where it is strongest: without
        // this, arcs nested n deep with two arcs each would list 2^n specs.
        std::vector<int32_t> out;
        std::unordered_set<int32_t> seen;
        for (const std::vector<int32_t>* list : std::initializer_list<const std::vector<int32_t>*>{&local, &inherits, &variants, &references, &specializes})
            for (int32_t s : *list)
                if (seen.insert(s).second) out.push_back(s);
        work_ += out.size();
        if (work_ > kMaxWork) {
            throw LimitExceeded(file_ + ": composing the file's arcs lists more than " + std::to_string(kMaxWork) +
                                " prim specs; refusing (a file built to multiply its prims?)");
        }
        return out;
    }

    void add_target(const Arc& arc, std::vector<int32_t>& out, const std::string& path, int depth)
    {
        if (!arc.asset.empty()) {
            say(where(arc.line) + ": <" + path + "> refers to another file (@" + arc.asset + "@" + (arc.path.empty() ? "" : "<" + arc.path + ">") +
                  "); other files are not read, so what it brings is left out");
            return;
        }
        std::string target = arc.path;
        if (target.empty()) {
            if (layer_.default_prim.empty()) {
                say(where(arc.line) + ": <" + path + "> refers to this file's default prim, but the file names none; arc left out");
                return;
            }
            target = "/" + layer_.default_prim;
        }
        if (path == target || (path.size() > target.size() && path.compare(0, target.size(), target) == 0 && path[target.size()] == '/')) {
            // An arc to the prim itself or an ancestor would nest the prim in itself without end.
            say(where(arc.line) + ": <" + path + "> refers to <" + target + ">, which contains it (a cycle); arc left out");
            return;
        }
        const std::vector<int32_t>* list = compose_path(target, depth + 1, arc.line, path);
        if (list) out.insert(out.end(), list->begin(), list->end());
    }

    /// The spec list of the prim at an absolute path (an arc's target), composed once and cached.
    const std::vector<int32_t>* compose_path(const std::string& target, int depth, size_t line, const std::string& from)
    {
        if (const auto it = cache_.find(target); it != cache_.end()) return &it->second;
        if (target.empty() || target[0] != '/' || in_progress_.count(target)) {
            say(where(line) + ": <" + from + "> refers to <" + target + ">, " + (in_progress_.count(target) ? "which refers back to it (a cycle)" : "not an absolute prim path") +
                  "; arc left out");
            return nullptr;
        }
        in_progress_.insert(target);
        std::vector<int32_t> list;
        std::vector<int32_t> candidates = layer_.roots;
        std::string sofar;
        size_t pos = 1;
        bool found = true;
        while (pos <= target.size() && found) {
            const size_t slash = std::min(target.find('/', pos), target.size());
            const std::string_view name(target.data() + pos, slash - pos);
            sofar = target.substr(0, slash);
            std::vector<int32_t> local;
            for (int32_t c : candidates)
                if (spec(c).name == name) local.push_back(c);
            if (local.empty()) {
                found = false;
                break;
            }
            list = expand(local, sofar, depth);
            candidates.clear();
            for (int32_t s : list) candidates.insert(candidates.end(), spec(s).children.begin(), spec(s).children.end());
            pos = slash + 1;
        }
        in_progress_.erase(target);
        if (!found) {
            say(where(line) + ": <" + from + "> refers to <" + target + ">, which is not in the file; arc left out");
            return nullptr;
        }
        return &cache_.emplace(target, std::move(list)).first->second;
    }

    bool selected(const std::string& path)
    {
        bool any = selected_.empty();
        for (size_t i = 0; i < selected_.size(); ++i) {
            const std::string& s = selected_[i];
            if (path == s) matched_[i] = true;
            if (path == s || (path.size() > s.size() && path.compare(0, s.size(), s) == 0 && path[s.size()] == '/')) any = true;
        }
        return any;
    }

    void visit(const std::string& path, const std::vector<int32_t>& specs, const Matrix4& parent_world, bool selected_above, int depth)
    {
        if (depth > kMaxPrimDepth) {
            throw LimitExceeded(where(spec(specs.front()).line) + ": <" + path.substr(0, 200) + "...>: prims nested deeper than " + std::to_string(kMaxPrimDepth) +
                                " levels once composed; refusing to read further");
        }
        // Specifier, active and type: the strongest opinion. A prim only `over`ed is not defined, a
        // `class` is abstract: neither is geometry, nor are their descendants (UsdPrimDefaultPredicate).
        std::optional<bool> active;
        std::string specifier, type_name;
        for (int32_t s : specs) {
            const PrimSpec& p = spec(s);
            if (!active && p.active) active = p.active;
            if (specifier.empty() && (p.specifier == "def" || p.specifier == "class")) specifier = p.specifier;
            if (type_name.empty()) type_name = p.type_name;
        }
        if (active == false || specifier != "def") return;

        PropertyView props;
        for (int32_t s : specs)
            for (const auto& [name, prop] : spec(s).props) props.emplace(name, &prop);
        LocalXform local;
        try {
            local = local_xform(props, file_, path);
        }
        catch (const ParseError& e) {
            skipped_.push_back(e.what());
            say(std::string(e.what()) + "; skipped <" + path + "> and the prims under it");
            return;
        }
        const Matrix4 world = local.resets ? local.matrix : multiply(parent_world, local.matrix);
        const bool here = selected_above || selected(path);
        if (here && (type_name == "BasisCurves" || type_name == "NurbsCurves")) {
            out_.push_back(ComposedCurves{path, type_name, spec(specs.front()).line, std::move(props), world});
        }
        std::vector<int32_t> children;
        for (int32_t s : specs) children.insert(children.end(), spec(s).children.begin(), spec(s).children.end());
        if (children.empty()) return;
        if (specs.size() == 1) {
            // One spec: its children are already one per name.
            for (int32_t c : children) visit(path + "/" + spec(c).name, expand({c}, path + "/" + spec(c).name, 0), world, here, depth + 1);
            return;
        }
        for (const auto& [name, local_specs] : group_children(children)) {
            const std::string child = path + "/" + name;
            visit(child, expand(local_specs, child, 0), world, here, depth + 1);
        }
    }

    const Layer& layer_;
    const std::string& file_;
    const std::vector<std::string>& selected_;
    std::vector<bool> matched_;
    const Warn& warn_;
    std::vector<std::string>& skipped_;
    std::unordered_map<std::string, std::vector<int32_t>> cache_;
    std::unordered_set<std::string> in_progress_;
    size_t work_ = 0;
    std::vector<ComposedCurves> out_;
};

}  // namespace

std::vector<ComposedCurves> compose_curves(const Layer& layer, const std::string& file_name, const std::vector<std::string>& selected,
                                           const Warn& warn, std::vector<std::string>& skipped)
{
    return Composer(layer, file_name, selected, warn, skipped).run();
}

}  // namespace groom::io::usda
