// scatterlut runtime — values as the table files store them: binary16 and binary32 rounding
// from double, the relative error a storage type costs, and the payload bytes every
// encoder (binary, EXR, KTX2) writes.
#include "scatterlut/io.hpp"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace scatterlut {

// binary16: 1 sign bit, 5 exponent bits (bias 15), 10 fraction bits. Normal numbers
// (1 + f/1024)·2^(e−15) for e = 1…30, subnormals (f/1024)·2^−14 = f·2^−24 for e = 0,
// ±inf / NaN for e = 31. Rounding works on the exact double bits: the kept fraction
// is the top bits of the 53-bit significand, the dropped bits decide the rounding
// (above half: up; exactly half: to even). A carry out of the fraction correctly
// increments the exponent (and 65520 → inf, the largest-normal tie going to even).
uint16_t f16_from_double(double x) {
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const uint16_t sign = static_cast<uint16_t>((bits >> 48) & 0x8000u);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    const uint64_t frac = bits & ((uint64_t{1} << 52) - 1);
    if (biased == 0x7ff) return static_cast<uint16_t>(sign | (frac ? 0x7e00u : 0x7c00u)); // NaN / inf
    const int e = biased - 1023; // x = 1.frac · 2^e for normal doubles
    if (biased == 0 || e < -25) {
        // Double subnormals and anything below 2^−25 (half the smallest subnormal)
        // round to zero; exactly 2^−25 is a tie that goes to the even 0.
        return sign;
    }
    if (e > 15) return static_cast<uint16_t>(sign | 0x7c00u); // ≥ 65536: overflow
    const uint64_t sig = (uint64_t{1} << 52) | frac;         // 53-bit significand
    uint64_t kept;
    int shift; // number of dropped bits
    uint16_t exp_field;
    if (e >= -14) { // normal half: keep 11 significant bits (implicit 1 included)
        shift = 42;
        exp_field = static_cast<uint16_t>((e + 15) << 10);
        kept = (sig >> shift) & 0x3ffu;
    } else { // subnormal half: value = sig·2^(e−52) in units of 2^−24
        shift = 28 - e; // 43 … 53
        exp_field = 0;
        kept = sig >> shift;
    }
    const uint64_t dropped = sig & ((uint64_t{1} << shift) - 1);
    const uint64_t half = uint64_t{1} << (shift - 1);
    uint32_t h = exp_field + static_cast<uint32_t>(kept);
    if (dropped > half || (dropped == half && (kept & 1u))) ++h; // carries into the exponent
    return static_cast<uint16_t>(sign | h);
}

double double_from_f16(uint16_t h) {
    const int e = (h >> 10) & 0x1f;
    const int f = h & 0x3ff;
    double v;
    if (e == 0) v = std::ldexp(static_cast<double>(f), -24);
    else if (e == 31) v = f ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
    else v = std::ldexp(static_cast<double>(1024 + f), e - 25);
    return (h & 0x8000u) ? -v : v;
}

namespace {

// double → float, round to nearest even, with overflow made explicit: a double
// outside the float range is undefined behaviour for static_cast. FLT_MAX = 2^128 − 2^104;
// the midpoint to 2^128 is 2^128 − 2^103 and ties go to the even 2^128 (= inf).
float f32_from_double(double x) {
    if (std::isnan(x)) return std::numeric_limits<float>::quiet_NaN();
    if (std::fabs(x) > static_cast<double>(FLT_MAX)) {
        const double limit = 0x1.ffffffp127; // 2^128 − 2^103
        return static_cast<float>(std::copysign(std::fabs(x) < limit ? static_cast<double>(FLT_MAX)
                                                                     : std::numeric_limits<double>::infinity(),
                                                x));
    }
    return static_cast<float>(x);
}

} // namespace

double round_to_storage(double x, Storage s) {
    switch (s) {
    case Storage::F16: return double_from_f16(f16_from_double(x));
    case Storage::F32: return static_cast<double>(f32_from_double(x));
    case Storage::F64: return x;
    }
    throw std::invalid_argument("round_to_storage: unknown storage id " + std::to_string(static_cast<uint32_t>(s)));
}

namespace detail {

std::string describe_value(const Table &t, size_t i) {
    std::ostringstream s;
    const size_t nc = t.channels.empty() ? 1 : t.channels.size();
    size_t rest = i / nc;
    s << "node (";
    for (size_t a = 0; a < t.axes.size(); ++a) {
        const size_t c = t.axes[a].map.count > 0 ? static_cast<size_t>(t.axes[a].map.count) : 1;
        s << (a ? ", " : "") << rest % c;
        rest /= c;
    }
    s << ")";
    if (i % nc < t.channels.size()) s << ", channel '" << t.channels[i % nc].name << "'";
    return s.str();
}

} // namespace detail

double storage_rounding_max_rel(const Table &t, Storage s) {
    if (storage_bytes(s) == 0)
        throw std::invalid_argument("storage_rounding_max_rel: unknown storage id " +
                                    std::to_string(static_cast<uint32_t>(s)));
    const size_t nc = t.channels.size();
    double worst = 0.0;
    for (size_t i = 0; i < t.values.size(); ++i) {
        const double v = t.values[i];
        if (!std::isfinite(v))
            throw std::invalid_argument("storage_rounding_max_rel: value at " + detail::describe_value(t, i) +
                                        " is not finite");
        const double r = round_to_storage(v, s);
        if (!std::isfinite(r)) return std::numeric_limits<double>::infinity();
        const bool log = nc && t.channels[i % nc].encoding == Encoding::Log;
        double rel;
        if (log) rel = std::fabs(std::expm1(r - v)); // exp(r)/exp(v) − 1, no cancellation
        else if (v == 0.0) rel = 0.0;                // 0 is exact in every storage type
        else rel = std::fabs(r - v) / std::fabs(v);
        if (rel > worst) worst = rel;
    }
    return worst;
}

namespace detail {

std::vector<uint8_t> encode_payload(const Table &t) {
    const size_t n = t.values.size();
    const size_t bytes = storage_bytes(t.storage);
    std::vector<uint8_t> out(n * bytes);
    uint8_t *p = out.data();
    for (size_t i = 0; i < n; ++i, p += bytes) {
        const double v = t.values[i];
        if (!std::isfinite(v))
            throw std::invalid_argument("value at " + describe_value(t, i) + " is not finite");
        uint64_t u = 0;
        switch (t.storage) {
        case Storage::F16: {
            const uint16_t h = f16_from_double(v);
            if ((h & 0x7c00u) == 0x7c00u) {
                std::ostringstream s;
                s.precision(17);
                s << "value " << v << " at " << describe_value(t, i)
                  << " overflows f16 (largest finite 65504); store the table as f32";
                throw std::invalid_argument(s.str());
            }
            u = h;
            break;
        }
        case Storage::F32: {
            const float f = f32_from_double(v);
            if (std::isinf(f)) {
                std::ostringstream s;
                s.precision(17);
                s << "value " << v << " at " << describe_value(t, i) << " overflows f32; store the table as f64";
                throw std::invalid_argument(s.str());
            }
            uint32_t w;
            std::memcpy(&w, &f, 4);
            u = w;
            break;
        }
        case Storage::F64: std::memcpy(&u, &v, 8); break;
        }
        for (size_t k = 0; k < bytes; ++k) p[k] = static_cast<uint8_t>(u >> (8 * k));
    }
    return out;
}

} // namespace detail

} // namespace scatterlut
