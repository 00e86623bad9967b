// The registry of table kinds: the one list of their descriptors (table_kind.hpp), in the
// order of the runtime facets' registry (kinds/runtime_registry.cpp), where names are compared.
#include <stdexcept>

#include "kinds/table_kind.hpp"

namespace scatterlut {

// Each kind's file defines its instances.
const std::vector<const TableKind *> &airlight_table_kinds();   // kinds/airlight_kind.cpp
const std::vector<const TableKind *> &near_light_table_kinds(); // kinds/nearlight_kind.cpp
const std::vector<const TableKind *> &surface_table_kinds();    // kinds/surface_kind.cpp
const std::vector<const TableKind *> &airlight_rational_table_kinds(); // kinds/airlight_rational_kind.cpp

const std::vector<const TableKind *> &table_kinds() {
    static const std::vector<const TableKind *> kinds = [] {
        std::vector<const TableKind *> defined, ordered;
        for (const auto *of_file : {&airlight_table_kinds(), &near_light_table_kinds(), &surface_table_kinds(),
                                    &airlight_rational_table_kinds()})
            defined.insert(defined.end(), of_file->begin(), of_file->end());
        for (const RuntimeKind *runtime : runtime_kinds())
            for (const TableKind *k : defined)
                if (&k->runtime() == runtime) ordered.push_back(k);
        if (ordered.size() != defined.size() || ordered.size() != runtime_kinds().size())
            throw std::logic_error("every table kind needs its own runtime facet in kinds/runtime_registry.cpp");
        return ordered;
    }();
    return kinds;
}

const TableKind *find_table_kind(const std::string &name) {
    const RuntimeKind *runtime = find_runtime_kind(name);
    for (const TableKind *k : table_kinds())
        if (&k->runtime() == runtime) return k;
    return nullptr;
}

} // namespace scatterlut
