/* Pinocchio peer (header-only use: no libpinocchio_* is linked). Chain scene only.
 *
 * Methods
 *   0 pinocchio_rnea          rnea(model, data, q, v, a); reactions are data.f (joint frames);
 *                             reaction() rotates them to world axes outside the timed call
 *   1 pinocchio_rnea_world    rnea, then data.oMi[i] = oMi[parent] * liMi[i] (rnea itself fills
 *                             liMi but not oMi) and every data.f[i] mapped to the world frame with
 *                             data.oMi[i].act() (world axes, moment about the world origin) into a
 *                             preallocated array
 *   2 pinocchio_crba_cholesky crba + nonLinearEffects + dense Cholesky (Eigen LLT, preallocated):
 *                             forward dynamics a = M^-1 (tau - nle) with tau = the rnea torques
 *                             computed at construction (the "CRBA + dense Cholesky" reference row);
 *                             torques() then reports that tau and reaction() the reactions of the
 *                             construction's rnea (this method computes none).
 *
 * Reactions: data.f[i] is the spatial force the parent exerts on body i through joint i,
 * expressed in joint i's frame (origin at the joint point), gravity and subtree inertia
 * included; its moment contains the actuator torque (S^T f = tau_i).
 */
#if !defined(__cplusplus) || __cplusplus < 201703L
#error "pinocchio_peer.cpp needs C++17 (Pinocchio 4)"
#endif

/* the definitions Pinocchio's CMake target pinocchio::pinocchio_headers carries */
#ifndef BOOST_MPL_LIMIT_LIST_SIZE
#define BOOST_MPL_LIMIT_LIST_SIZE 30
#endif
#ifndef BOOST_MPL_LIMIT_VECTOR_SIZE
#define BOOST_MPL_LIMIT_VECTOR_SIZE 30
#endif
#ifndef BOOST_MPL_CFG_NO_PREPROCESSED_HEADERS
#define BOOST_MPL_CFG_NO_PREPROCESSED_HEADERS
#endif
#ifndef BOOST_FUSION_INVOKE_MAX_ARITY
#define BOOST_FUSION_INVOKE_MAX_ARITY 12
#endif
/* header-only: the explicit instantiations live in libpinocchio_default, which is not linked */
#undef PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION
/* The peer is timed as a released build: Eigen's and Pinocchio's assert()s off in this file even
 * when the benchmark is configured with b_ndebug=false (Meson's default, also for buildtype
 * release); they double the rnea time at n = 100. */
#ifndef NDEBUG
#define NDEBUG
#endif
#ifndef EIGEN_NO_DEBUG
#define EIGEN_NO_DEBUG
#endif

/* With -march=native on an AVX-512 machine GCC 12 reports, inside its own intrinsics headers
 * where Eigen's kernels get inlined into this file, a false -Wmaybe-uninitialized (the
 * "__Y = __Y" idiom, GCC bug 105593) and -Warray-bounds / -Wstringop-overread on 8-double
 * packets of 6-vectors in branches Eigen never takes. -isystem does not silence diagnostics
 * reported at the inlining site, and the project builds with -Werror: ignore them here. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wstringop-overread"
#endif

#include <cstdlib>
#include <new>
#include <vector>

#include <Eigen/Cholesky>
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/crba.hpp>

#include "peer_impl.h"

namespace {

namespace pin = pinocchio;

const char *const pin_method_names[] = {
    "pinocchio_rnea",
    "pinocchio_rnea_world",
    "pinocchio_crba_cholesky",
};

struct PinPeer {
    pin::Model model;
    pin::Data data;
    Eigen::VectorXd q, v, a;
    Eigen::VectorXd tau0;  /* rnea torques at construction: the right-hand side of method 2 */
    Eigen::VectorXd acc;   /* method 2: M^-1 (tau0 - nle) */
    Eigen::LLT<Eigen::MatrixXd> llt;
    std::vector<pin::Force> fworld;  /* method 1: oMi[i].act(f[i]), i = 1..n (index 0 unused) */
    std::vector<pin::Force> fworld0; /* the same at construction (reported after method 2) */
    std::vector<Eigen::Vector3d> o0; /* joint positions at construction */
    int last;              /* last method run */

    /* the chain of n links */
    static pin::Model make_chain(int n)
    {
        pin::Model model;
        model.gravity = pin::Motion(Eigen::Vector3d(0.0, -9.81, 0.0), Eigen::Vector3d::Zero());
        /* link k: 1 kg, 0.5 m along its x, COM at +0.25, inertia about the COM diag(2e-4, 1/48, 1/48) */
        const pin::Inertia link(1.0, Eigen::Vector3d(0.25, 0.0, 0.0),
                                Eigen::Vector3d(2e-4, 1.0 / 48.0, 1.0 / 48.0).asDiagonal().toDenseMatrix());
        pin::JointIndex parent = 0;
        for (int k = 1; k <= n; k++) {
            const pin::SE3 place(Eigen::Matrix3d::Identity(),
                                 Eigen::Vector3d(k > 1 ? 0.5 : 0.0, 0.0, 0.0));
            const std::string name = "j" + std::to_string(k);
            pin::JointIndex id;
            switch ((k - 1) % 3) {
            case 0: id = model.addJoint(parent, pin::JointModelRX(), place, name); break;
            case 1: id = model.addJoint(parent, pin::JointModelRY(), place, name); break;
            default: id = model.addJoint(parent, pin::JointModelRZ(), place, name); break;
            }
            model.appendBodyToJoint(id, link, pin::SE3::Identity());
            parent = id;
        }
        return model;
    }

    /* data and llt built in place: copying an Eigen LLT (Data holds some) reads its
     * ComputationInfo before any compute() has set it */
    PinPeer(int n, const double *q0, const double *qd0, const double *qdd0)
        : model(make_chain(n)), data(model), llt(n)
    {
        q = Eigen::Map<const Eigen::VectorXd>(q0, n);
        v = Eigen::Map<const Eigen::VectorXd>(qd0, n);
        a = Eigen::Map<const Eigen::VectorXd>(qdd0, n);
        acc = Eigen::VectorXd::Zero(n);
        fworld.assign(static_cast<size_t>(n) + 1, pin::Force::Zero());
        run(1);
        tau0 = data.tau;
        fworld0 = fworld;
        o0.resize(fworld.size());
        for (size_t i = 1; i < o0.size(); i++) o0[i] = data.oMi[i].translation();
    }

    void to_world()
    {
        for (pin::JointIndex i = 1; i < static_cast<pin::JointIndex>(model.njoints); i++) {
            const pin::JointIndex parent = model.parents[i];
            if (parent > 0) data.oMi[i] = data.oMi[parent] * data.liMi[i];
            else data.oMi[i] = data.liMi[i];
            fworld[i] = data.oMi[i].act(data.f[i]);
        }
    }

    void run(int method)
    {
        switch (method) {
        case 0:
            pin::rnea(model, data, q, v, a);
            break;
        case 1:
            pin::rnea(model, data, q, v, a);
            to_world();
            break;
        default:
            pin::crba(model, data, q);
            data.M.triangularView<Eigen::StrictlyLower>() = data.M.transpose().triangularView<Eigen::StrictlyLower>();
            pin::nonLinearEffects(model, data, q, v);
            llt.compute(data.M);
            acc = tau0 - data.nle;
            llt.solveInPlace(acc);
            break;
        }
        last = method;
    }
};

PinPeer *impl(void *p) { return static_cast<PinPeer *>(p); }
const PinPeer *impl(const void *p) { return static_cast<const PinPeer *>(p); }

void pin_run(void *p, int method) { impl(p)->run(method); }

void pin_torques(const void *p, double *tau)
{
    const PinPeer *s = impl(p);
    const Eigen::VectorXd &t = s->last == 2 ? s->tau0 : s->data.tau;
    for (Eigen::Index i = 0; i < t.size(); i++) tau[i] = t[i];
}

void pin_reaction(const void *p, int k, double f[3], double n[3])
{
    const PinPeer *s = impl(p);
    Eigen::Vector3d fw, nw;
    if (s->last == 0) {
        /* joint frame (origin at the joint point): rotate to world axes, R = product of the
         * rotations of liMi along the path (data.oMi is not filled by rnea) */
        Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
        std::vector<pin::JointIndex> path;
        for (pin::JointIndex i = static_cast<pin::JointIndex>(k); i > 0; i = s->model.parents[i]) path.push_back(i);
        for (auto it = path.rbegin(); it != path.rend(); ++it) R = R * s->data.liMi[*it].rotation();
        fw = R * s->data.f[k].linear();
        nw = R * s->data.f[k].angular();
    } else {
        /* world axes about the world origin -> about the joint point o: n_o = n_0 - o x f, with
         * o = the joint's world position (data.oMi, filled with fworld) */
        const std::vector<pin::Force> &F = s->last == 1 ? s->fworld : s->fworld0;
        const Eigen::Vector3d o = s->last == 1 ? Eigen::Vector3d(s->data.oMi[k].translation()) : s->o0[k];
        fw = F[k].linear();
        nw = F[k].angular() - o.cross(fw);
    }
    for (int j = 0; j < 3; j++) {
        f[j] = fw[j];
        n[j] = nw[j];
    }
}

void pin_destroy(void *p) { delete impl(p); }

const vt_peer_vtable pin_vtable = {
    3, pin_method_names, pin_run, pin_torques, pin_reaction, pin_destroy,
};

} // namespace

extern "C" vt_peer *vt_peer_pinocchio(int scene, int n, const double *q, const double *qd, const double *qdd)
{
    if (scene != VT_PEER_CHAIN || n < 1 || !q || !qd || !qdd) return nullptr;
    vt_peer *p = static_cast<vt_peer *>(std::malloc(sizeof *p));
    if (!p) return nullptr;
    try {
        p->impl = new PinPeer(n, q, qd, qdd);
    } catch (...) {
        std::free(p);
        return nullptr;
    }
    p->vt = &pin_vtable;
    p->n = n;
    return p;
}

/* for tests (declared nowhere public): the accelerations of the last pinocchio_crba_cholesky run */
extern "C" void vt_peer_pinocchio_acc(const vt_peer *p, double *acc);
extern "C" void vt_peer_pinocchio_acc(const vt_peer *p, double *acc)
{
    const PinPeer *s = impl(p->impl);
    for (Eigen::Index i = 0; i < s->acc.size(); i++) acc[i] = s->acc[i];
}
