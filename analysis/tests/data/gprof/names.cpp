// C++ names as gprof prints them demangled: namespaces, templates, operators,
// const members, an anonymous namespace, for the importer's name tests. Build:
// g++ -pg -O1 names.cpp.
#include <cstdio>
#include <vector>

namespace rt {
template <typename T> struct Vec {
    T x, y, z;
};

template <typename T>
__attribute__((noinline)) T dot(const Vec<T> &a, const Vec<T> &b)
{
    T s = 0;
    for (int k = 0; k < 20000; k++)
        s += a.x * b.x + a.y * b.y + a.z * b.z + k;
    return s;
}

struct Sphere {
    Vec<double> c;
    double r;
    __attribute__((noinline)) bool intersect(const Vec<double> &o) const { return dot(c, o) > r; }
    __attribute__((noinline)) bool operator()(int n) const
    {
        Vec<double> v{double(n), 1, 2};
        return intersect(v);
    }
};
} // namespace rt

namespace {
__attribute__((noinline)) int trace(const std::vector<rt::Sphere> &s, int i)
{
    int h = 0;
    for (auto &x : s)
        h += x(i);
    return h;
}
} // namespace

int main()
{
    std::vector<rt::Sphere> s(7, rt::Sphere{{1, 2, 3}, 4});
    long h = 0;
    for (int i = 0; i < 3000; i++)
        h += trace(s, i);
    std::printf("%ld\n", h);
}
