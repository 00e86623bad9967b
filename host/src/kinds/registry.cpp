// The registry of table kinds: the one list of their descriptors (table_kind.hpp); names are
// compared in kinds/runtime_registry.cpp.
#include "kinds/table_kind.hpp"

namespace scatterlut {

// Each kind's file defines its instance.
const TableKind &airlight_table_kind();
const TableKind &near_light_thick_table_kind();
const TableKind &near_light_slab_table_kind();
const TableKind &airlight_hg_table_kind();
const TableKind &near_light_thick_hg_table_kind();
const TableKind &near_light_slab_hg_table_kind();
const TableKind &surface_table_kind();

const std::vector<const TableKind *> &table_kinds() {
    static const std::vector<const TableKind *> kinds = {&airlight_table_kind(), &near_light_thick_table_kind(),
                                                         &near_light_slab_table_kind(), &airlight_hg_table_kind(),
                                                         &near_light_thick_hg_table_kind(), &near_light_slab_hg_table_kind(),
                                                         &surface_table_kind()};
    return kinds;
}

const TableKind *find_table_kind(const std::string &name) {
    const RuntimeKind *runtime = find_runtime_kind(name);
    for (const TableKind *k : table_kinds())
        if (&k->runtime() == runtime) return k;
    return nullptr;
}

} // namespace scatterlut
