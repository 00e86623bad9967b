// The registry of the kinds' runtime facets (runtime_kind.hpp): the one place a kind's name
// is compared with a string.
#include "kinds/runtime_kind.hpp"

namespace scatterlut {

// Each kind's runtime file defines its facet.
const RuntimeKind &airlight_runtime_kind();
const RuntimeKind &near_light_thick_runtime_kind();
const RuntimeKind &near_light_slab_runtime_kind();
const RuntimeKind &airlight_hg_runtime_kind();
const RuntimeKind &surface_runtime_kind();
const RuntimeKind &near_light_thick_hg_runtime_kind();
const RuntimeKind &near_light_slab_hg_runtime_kind();

const std::vector<const RuntimeKind *> &runtime_kinds() {
    static const std::vector<const RuntimeKind *> kinds = {&airlight_runtime_kind(), &near_light_thick_runtime_kind(),
                                                           &near_light_slab_runtime_kind(), &airlight_hg_runtime_kind(),
                                                           &near_light_thick_hg_runtime_kind(), &near_light_slab_hg_runtime_kind(),
                                                           &surface_runtime_kind()};
    return kinds;
}

const RuntimeKind *find_runtime_kind(const std::string &name) {
    for (const RuntimeKind *k : runtime_kinds())
        if (name == k->name()) return k;
    return nullptr;
}

} // namespace scatterlut
