// The registry of the kinds' runtime facets (runtime_kind.hpp): the one place a kind's name
// is compared with a string, and the one order of the kinds (plans, output sets, reports and
// eval list them so; table_kinds() follows it).
#include "kinds/runtime_kind.hpp"

namespace scatterlut {

const std::vector<const RuntimeKind *> &runtime_kinds() {
    static const std::vector<const RuntimeKind *> kinds = {
        &airlight_runtime_kind(false),          // airlight_F
        &near_light_runtime_kind(false, false), // near_light_E3
        &near_light_runtime_kind(true, false),  // near_light_E4
        &airlight_runtime_kind(true),           // airlight_Fg
        &near_light_runtime_kind(false, true),  // near_light_E3_hg
        &near_light_runtime_kind(true, true),   // near_light_E4_hg
        &surface_runtime_kind(),                // surface_G
        &airlight_rational_runtime_kind()};     // airlight_rational
    return kinds;
}

const RuntimeKind *find_runtime_kind(const std::string &name) {
    for (const RuntimeKind *k : runtime_kinds())
        if (name == k->name()) return k;
    return nullptr;
}

} // namespace scatterlut
