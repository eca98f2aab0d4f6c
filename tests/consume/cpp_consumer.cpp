// The C API from C++ (vtdyn.h's extern "C"), built with -Wall -Wextra -Werror: the paper's
// double link, joint 2 locked, at one instant (θ = 0.5 rad, θ̇² = 7.3575 sin θ); the locking
// torque must be 245.25 cos θ and θ̈ = 3.67875 cos θ (eq. (29)'s solution), to 1e-10 relative.
// The model and data are owned by unique_ptrs with the library's free functions as deleters.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include <vtdyn.h>

namespace {

using model_ptr = std::unique_ptr<vt_model, decltype(&vt_model_free)>;
using data_ptr = std::unique_ptr<vt_data, decltype(&vt_data_free)>;
using builder_ptr = std::unique_ptr<vt_builder, decltype(&vt_builder_free)>;

model_ptr double_link()
{
    vt_builder *raw = nullptr;
    if (vt_builder_create(&raw, nullptr) != VT_OK) return model_ptr(nullptr, vt_model_free);
    builder_ptr b(raw, vt_builder_free);
    vt_body_def link = vt_default_body_def();
    link.mass = 100.0;
    link.inertia[4] = link.inertia[8] = 100.0 * 4.0 / 12.0;
    link.joint_child[0] = -1.0;
    const int l1 = vt_builder_add_body(b.get(), &link);
    link.parent = l1;
    link.joint_parent[0] = 1.0;
    const int l2 = vt_builder_add_body(b.get(), &link);
    vt_drive_def lock = vt_default_drive_def();
    lock.body = l2;
    vt_model *m = nullptr;
    if (l2 != 2 || vt_builder_add_drive(b.get(), &lock) != 0 || vt_builder_build(&m, b.get()) != VT_OK)
        std::fprintf(stderr, "cpp_consumer: %s\n", vt_builder_message(b.get()));
    return model_ptr(m, vt_model_free);
}

bool near(const char *what, double got, double want, double scale)
{
    if (std::fabs(got - want) <= 1e-10 * scale) return true;
    std::fprintf(stderr, "cpp_consumer: %s = %.17g, expected %.17g\n", what, got, want);
    return false;
}

} // namespace

int main()
{
    model_ptr m = double_link();
    if (!m) return 1;
    vt_data *raw = nullptr;
    if (vt_data_create(&raw, m.get()) != VT_OK) return 1;
    data_ptr d(raw, vt_data_free);
    const double th = 0.5, s = std::sin(th), c = std::cos(th);
    d->q[0] = -th;
    d->qd[0] = -std::sqrt(7.3575 * s);
    const vt_status st = vt_inverse_dynamics(m.get(), d.get());
    if (st != VT_OK) {
        std::fprintf(stderr, "cpp_consumer: %s: %s\n", vt_status_string(st), d->message);
        return 1;
    }
    bool ok = near("theta_ddot", -d->qdd[0], 3.67875 * c, 3.67875);
    ok = near("locking torque", std::fabs(d->drive_effort[0]), 245.25 * c, 245.25) && ok;
    ok = std::strcmp(vt_version(), VT_VERSION_STRING) == 0 && ok;
    std::printf("vtdyn %s from C++: locking torque %.12g N m\n", vt_version(), d->drive_effort[0]);
    return ok ? 0 : 1;
}
