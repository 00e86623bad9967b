// The airlight_rational table's runtime facet (kinds/runtime_kind.hpp): its sampler,
// AirlightRationalTable (tables/src/airlight_rational.cpp), and no eval quantity of its own:
// eval answers "airlight" queries from a loaded airlight_F table (kinds/airlight_runtime.cpp).
// Its descriptor: kinds/airlight_rational_kind.cpp.
#include "kinds/runtime_kind.hpp"
#include "scatterlut/airlight_rational.hpp"

namespace scatterlut {

const RuntimeKind &airlight_rational_runtime_kind() {
    static const RuntimeKindOf<AirlightRationalTable> kind(kKindAirlightRational);
    return kind;
}

} // namespace scatterlut
