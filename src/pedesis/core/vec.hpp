#pragma once
// A small fixed-dimension vector. D is a template parameter everywhere so that
// loops over components unroll and no `if (dim == 2)` appears in hot code.
#include <array>
#include <cmath>
#include <cstddef>

namespace pedesis {

template <int D> struct Vec {
    std::array<double, D> c{};

    constexpr double& operator[](std::size_t a) { return c[a]; }
    constexpr double operator[](std::size_t a) const { return c[a]; }

    static constexpr Vec filled(double x) {
        Vec v;
        for (int a = 0; a < D; ++a) v.c[a] = x;
        return v;
    }

    constexpr Vec& operator+=(const Vec& o) {
        for (int a = 0; a < D; ++a) c[a] += o.c[a];
        return *this;
    }
    constexpr Vec& operator-=(const Vec& o) {
        for (int a = 0; a < D; ++a) c[a] -= o.c[a];
        return *this;
    }
    constexpr Vec& operator*=(double s) {
        for (int a = 0; a < D; ++a) c[a] *= s;
        return *this;
    }
    friend constexpr Vec operator+(Vec a, const Vec& b) { return a += b; }
    friend constexpr Vec operator-(Vec a, const Vec& b) { return a -= b; }
    friend constexpr Vec operator*(Vec a, double s) { return a *= s; }
    friend constexpr Vec operator*(double s, Vec a) { return a *= s; }
    friend constexpr Vec operator-(Vec a) { return a *= -1.0; }
    friend constexpr bool operator==(const Vec&, const Vec&) = default;
};

template <int D> constexpr double dot(const Vec<D>& a, const Vec<D>& b) {
    double s = 0.0;
    for (int k = 0; k < D; ++k) s += a[k] * b[k];
    return s;
}

template <int D> constexpr double norm2(const Vec<D>& a) {
    return dot(a, a);
}
template <int D> inline double norm(const Vec<D>& a) {
    return std::sqrt(norm2(a));
}

template <int D> inline bool all_finite(const Vec<D>& a) {
    for (int k = 0; k < D; ++k)
        if (!std::isfinite(a[k])) return false;
    return true;
}

} // namespace pedesis
