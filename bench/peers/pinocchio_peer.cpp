/* Pinocchio peer (header-only use: no libpinocchio_* is linked). The chain scene, and URDF robots
 * (vt_peer_pinocchio_robot: the model built here from the URDF file as Pinocchio's own loader
 * builds it, see RobotBuilder below; the loader itself lives in libpinocchio_parsers, which is
 * not linked for the reason given in meson.build).
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

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef VT_PEER_URDF
#include <libxml/parser.h>
#include <libxml/tree.h>
#endif

#include <Eigen/Cholesky>
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/joint-configuration.hpp>

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

#ifdef VT_PEER_URDF
/* ---- URDF robots ----
 * RobotBuilder: the model Pinocchio's buildModelFromUrdf makes (parsers/urdf/model.cpp), rebuilt
 * here from the file with libxml2: the links visited depth first from the root, a link's child
 * joints in the order of their names (urdfdom keeps its joints in a std::map); a revolute or
 * prismatic joint whose axis is +x, +y or +z becomes JointModelRX/RY/RZ (PX/PY/PZ), another
 * axis the unaligned joint; the joint's placement is its origin composed with the placement of
 * its parent link in the parent link's joint (fixed joints); a link's inertia (mass, COM at the
 * inertial origin, R I R^T) is appended to its joint, a link behind a fixed joint appended to the
 * joint it is fixed to at its placement; with floating, a JointModelFreeFlyer "root_joint" at the
 * root link's frame. Continuous, floating and planar joints are refused (none of the benchmark's
 * robots has one). */
struct RobotBuilder {
    struct Link { double mass = 0.0; Eigen::Vector3d com = Eigen::Vector3d::Zero(); Eigen::Matrix3d I = Eigen::Matrix3d::Zero(); };
    struct Joint { std::string name, type, parent, child; pin::SE3 origin = pin::SE3::Identity(); Eigen::Vector3d axis = Eigen::Vector3d::UnitX(); };
    std::map<std::string, Link> links;
    std::vector<Joint> joints;
    std::string error;

    static std::string attr(xmlNodePtr n, const char *name)
    {
        xmlChar *v = xmlGetProp(n, reinterpret_cast<const xmlChar *>(name));
        std::string s = v ? reinterpret_cast<const char *>(v) : "";
        xmlFree(v);
        return s;
    }
    static xmlNodePtr child(xmlNodePtr n, const char *name)
    {
        for (xmlNodePtr c = n->children; c; c = c->next)
            if (c->type == XML_ELEMENT_NODE && std::strcmp(reinterpret_cast<const char *>(c->name), name) == 0) return c;
        return nullptr;
    }
    static Eigen::Vector3d vec(const std::string &s, const Eigen::Vector3d &dflt)
    {
        if (s.empty()) return dflt;
        std::istringstream in(s);
        Eigen::Vector3d v;
        in >> v[0] >> v[1] >> v[2];
        return v;
    }
    static pin::SE3 origin(xmlNodePtr o)
    {
        if (!o) return pin::SE3::Identity();
        const Eigen::Vector3d xyz = vec(attr(o, "xyz"), Eigen::Vector3d::Zero()), rpy = vec(attr(o, "rpy"), Eigen::Vector3d::Zero());
        const Eigen::Matrix3d R = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX())).toRotationMatrix();
        return pin::SE3(R, xyz);
    }

    bool read(const char *path)
    {
        xmlDocPtr doc = xmlReadFile(path, nullptr, XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR);
        if (!doc) return error = std::string("cannot read ") + path, false;
        xmlNodePtr robot = xmlDocGetRootElement(doc);
        for (xmlNodePtr n = robot ? robot->children : nullptr; n; n = n->next) {
            if (n->type != XML_ELEMENT_NODE) continue;
            const char *tag = reinterpret_cast<const char *>(n->name);
            if (std::strcmp(tag, "link") == 0) {
                Link l;
                if (xmlNodePtr in = child(n, "inertial")) {
                    const pin::SE3 o = origin(child(in, "origin"));
                    xmlNodePtr ms = child(in, "mass"), it = child(in, "inertia");
                    l.mass = ms ? std::atof(attr(ms, "value").c_str()) : 0.0;
                    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
                    if (it) {
                        auto g = [&](const char *k) { return std::atof(attr(it, k).c_str()); };
                        I << g("ixx"), g("ixy"), g("ixz"), g("ixy"), g("iyy"), g("iyz"), g("ixz"), g("iyz"), g("izz");
                    }
                    l.com = o.translation();
                    l.I = o.rotation() * I * o.rotation().transpose();
                }
                links[attr(n, "name")] = l;
            } else if (std::strcmp(tag, "joint") == 0) {
                Joint j;
                j.name = attr(n, "name");
                j.type = attr(n, "type");
                j.parent = child(n, "parent") ? attr(child(n, "parent"), "link") : "";
                j.child = child(n, "child") ? attr(child(n, "child"), "link") : "";
                j.origin = origin(child(n, "origin"));
                if (xmlNodePtr a = child(n, "axis")) j.axis = vec(attr(a, "xyz"), Eigen::Vector3d::UnitX());
                joints.push_back(j);
            }
        }
        xmlFreeDoc(doc);
        if (links.empty()) return error = std::string("no links in ") + path, false;
        return true;
    }

    template <class JX, class JY, class JZ, class JU>
    static pin::JointModel axis_joint(const Eigen::Vector3d &axis)
    {
        if (axis.isApprox(Eigen::Vector3d::UnitX())) return JX();
        if (axis.isApprox(Eigen::Vector3d::UnitY())) return JY();
        if (axis.isApprox(Eigen::Vector3d::UnitZ())) return JZ();
        return JU(axis.normalized());
    }

    void visit(pin::Model &model, const std::map<std::string, std::map<std::string, size_t>> &kids, const std::string &link,
               pin::JointIndex jid, const pin::SE3 &place)
    {
        auto it = kids.find(link);
        if (it == kids.end()) return;
        for (const auto &kv : it->second) {
            const Joint &j = joints[kv.second];
            const Link &l = links[j.child];
            const pin::Inertia Y(l.mass, l.com, l.I);
            const pin::SE3 placement = place * j.origin;
            if (j.type == "fixed") {
                model.appendBodyToJoint(jid, Y, placement);
                visit(model, kids, j.child, jid, placement);
                continue;
            }
            pin::JointModel jm;
            if (j.type == "revolute")
                jm = axis_joint<pin::JointModelRX, pin::JointModelRY, pin::JointModelRZ, pin::JointModelRevoluteUnaligned>(j.axis);
            else if (j.type == "prismatic")
                jm = axis_joint<pin::JointModelPX, pin::JointModelPY, pin::JointModelPZ, pin::JointModelPrismaticUnaligned>(j.axis);
            else {
                if (error.empty()) error = "joint " + j.name + ": type " + j.type + " not supported here";
                continue;
            }
            const pin::JointIndex id = model.addJoint(jid, jm, placement, j.name);
            model.appendBodyToJoint(id, Y, pin::SE3::Identity());
            visit(model, kids, j.child, id, pin::SE3::Identity());
        }
    }

    bool build(pin::Model &model, bool floating)
    {
        std::map<std::string, std::map<std::string, size_t>> kids;
        std::map<std::string, int> is_child;
        for (size_t k = 0; k < joints.size(); k++) {
            kids[joints[k].parent][joints[k].name] = k;
            is_child[joints[k].child] = 1;
        }
        std::string root;
        for (const auto &l : links)
            if (!is_child.count(l.first)) {
                if (!root.empty()) return error = "two root links", false;
                root = l.first;
            }
        model.gravity = pin::Motion(Eigen::Vector3d(0.0, 0.0, -9.81), Eigen::Vector3d::Zero());
        const Link &r = links[root];
        pin::JointIndex jid = 0;
        if (floating) {
            jid = model.addJoint(0, pin::JointModelFreeFlyer(), pin::SE3::Identity(), "root_joint");
            model.appendBodyToJoint(jid, pin::Inertia(r.mass, r.com, r.I), pin::SE3::Identity());
        }
        visit(model, kids, root, jid, pin::SE3::Identity());
        return error.empty();
    }
};

/* A robot: the state arrives in vtdyn's layout (see peers.h) and is converted once. */
const char *const robot_method_names[] = {"pinocchio_rnea", "pinocchio_rnea_world"};

struct RobotPeer {
    pin::Model model;
    pin::Data data;
    Eigen::VectorXd q, v, a;
    std::vector<pin::Force> fworld;
    std::vector<pin::JointIndex> jid; /* Pinocchio's joint of vtdyn's joint k */
    std::vector<int> vadr;            /* vtdyn's first rate of joint k */
    int nv_vt = 0;
    Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity(); /* the free flyer's rotation */

    /* data built in place from the finished model (see PinPeer) */
    explicit RobotPeer(const pin::Model &m) : model(m), data(model) {}

    bool init(int nj, const char *const *names, const double *qv, const double *qdv, const double *qddv, std::string &err)
    {
        q = pin::neutral(model);
        v = Eigen::VectorXd::Zero(model.nv);
        a = Eigen::VectorXd::Zero(model.nv);
        int iq = 0, iv = 0;
        for (int k = 0; k < nj; k++) {
            const bool root = !names[k] || !names[k][0];
            const std::string name = root ? "root_joint" : names[k];
            if (!model.existJointName(name)) return err = "Pinocchio's model has no joint " + name, false;
            const pin::JointIndex id = model.getJointId(name);
            const int pq = model.joints[id].idx_q(), pv = model.joints[id].idx_v();
            jid.push_back(id);
            vadr.push_back(iv);
            if (root) {
                /* (x, y, z, w, x, y, z) -> (x, y, z, x, y, z, w); world rates -> the root frame's */
                const Eigen::Quaterniond quat(qv[iq + 3], qv[iq + 4], qv[iq + 5], qv[iq + 6]);
                R0 = quat.normalized().toRotationMatrix();
                for (int c = 0; c < 3; c++) q[pq + c] = qv[iq + c];
                q[pq + 3] = quat.x(); q[pq + 4] = quat.y(); q[pq + 5] = quat.z(); q[pq + 6] = quat.w();
                const Eigen::Vector3d pd(qdv + iv), w(qdv + iv + 3), pdd(qddv + iv), wd(qddv + iv + 3);
                const Eigen::Vector3d vl = R0.transpose() * pd, wl = R0.transpose() * w;
                v.segment<3>(pv) = vl;
                v.segment<3>(pv + 3) = wl;
                a.segment<3>(pv) = R0.transpose() * pdd - wl.cross(vl);
                a.segment<3>(pv + 3) = R0.transpose() * wd;
                iq += 7;
                iv += 6;
            } else {
                if (model.joints[id].nq() != 1) return err = "joint " + name + " has more than one coordinate", false;
                q[pq] = qv[iq++];
                v[pv] = qdv[iv];
                a[pv] = qddv[iv++];
            }
        }
        nv_vt = iv;
        if (iv != model.nv) return err = "the joints given do not cover Pinocchio's model", false;
        fworld.assign(static_cast<size_t>(model.njoints), pin::Force::Zero());
        run(1);
        return true;
    }

    void run(int method)
    {
        pin::rnea(model, data, q, v, a);
        if (method == 0) return;
        for (pin::JointIndex i = 1; i < static_cast<pin::JointIndex>(model.njoints); i++) {
            const pin::JointIndex parent = model.parents[i];
            if (parent > 0) data.oMi[i] = data.oMi[parent] * data.liMi[i];
            else data.oMi[i] = data.liMi[i];
            fworld[i] = data.oMi[i].act(data.f[i]);
        }
    }
};

RobotPeer *rimpl(void *p) { return static_cast<RobotPeer *>(p); }
const RobotPeer *rimpl(const void *p) { return static_cast<const RobotPeer *>(p); }

void robot_run(void *p, int method) { rimpl(p)->run(method); }

/* in vtdyn's layout: the free flyer's six as a world force and a world moment about the root
 * origin (R f, R n), every other joint's torque or force */
void robot_torques(const void *p, double *tau)
{
    const RobotPeer *s = rimpl(p);
    for (size_t k = 0; k < s->jid.size(); k++) {
        const pin::JointIndex id = s->jid[k];
        const int pv = s->model.joints[id].idx_v();
        if (s->model.joints[id].nv() == 6) {
            const Eigen::Vector3d f = s->R0 * s->data.tau.segment<3>(pv), n = s->R0 * s->data.tau.segment<3>(pv + 3);
            for (int c = 0; c < 3; c++) {
                tau[s->vadr[k] + c] = f[c];
                tau[s->vadr[k] + 3 + c] = n[c];
            }
        } else {
            tau[s->vadr[k]] = s->data.tau[pv];
        }
    }
}

/* vtdyn's joint k (1-based): world axes, the moment about the joint's origin, actuation inside;
 * the poses from liMi (rnea fills those) */
void robot_reaction(const void *p, int k, double f[3], double n[3])
{
    const RobotPeer *s = rimpl(p);
    const pin::JointIndex id = s->jid[static_cast<size_t>(k - 1)];
    pin::SE3 M = pin::SE3::Identity();
    std::vector<pin::JointIndex> path;
    for (pin::JointIndex i = id; i > 0; i = s->model.parents[i]) path.push_back(i);
    for (auto it = path.rbegin(); it != path.rend(); ++it) M = M * s->data.liMi[*it];
    const Eigen::Vector3d fw = M.rotation() * s->data.f[id].linear(), nw = M.rotation() * s->data.f[id].angular();
    for (int j = 0; j < 3; j++) {
        f[j] = fw[j];
        n[j] = nw[j];
    }
}

void robot_destroy(void *p) { delete rimpl(p); }

const vt_peer_vtable robot_vtable = {
    2, robot_method_names, robot_run, robot_torques, robot_reaction, robot_destroy,
};
#endif

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

#ifdef VT_PEER_URDF
extern "C" vt_peer *vt_peer_pinocchio_robot(const char *urdf, int floating, int nj, const char *const *names,
                                            const double *q, const double *qd, const double *qdd, char *message)
{
    if (message) message[0] = '\0';
    if (!urdf || nj < 1 || !names || !q || !qd || !qdd) return nullptr;
    vt_peer *p = static_cast<vt_peer *>(std::malloc(sizeof *p));
    if (!p) return nullptr;
    RobotPeer *r = nullptr;
    std::string err;
    try {
        RobotBuilder b;
        pin::Model model;
        if (!b.read(urdf) || !b.build(model, floating != 0)) throw std::runtime_error(b.error);
        r = new RobotPeer(model);
        if (!r->init(nj, names, q, qd, qdd, err)) {
            delete r;
            r = nullptr;
        }
    } catch (const std::exception &e) {
        delete r;
        r = nullptr;
        err = e.what();
    }
    if (!r) {
        if (message) std::snprintf(message, 256, "%s", err.c_str());
        std::free(p);
        return nullptr;
    }
    p->impl = r;
    p->vt = &robot_vtable;
    p->n = nj;
    return p;
}
#endif
