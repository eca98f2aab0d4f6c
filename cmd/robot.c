/* The command's robot: the URDF loaded with the command's options, and the joint types' names. */
#include "robot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "message.h"

int cmd_load_urdf(vt_builder **b, const char *path, int floating)
{
    char msg[VT_MESSAGE_SIZE] = "";
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = floating;
    opt.mimic = 0; /* every joint its own column: a mimic joint's effort is what it needs itself */
    opt.model.layout = VT_LAYOUT_RECURSIVE; /* the rows' given motion and kinematic solve: O(n) data */
    const vt_status st = vt_urdf_builder(b, path, &opt, msg);
    if (st) return cmd_fail("%s: %s (%s)", path, msg, vt_status_string(st));
    return 0;
}

int cmd_add_payload(vt_builder *b, const char *spec, const char *path)
{
    const char *comma = strchr(spec, ',');
    char link[VT_NAME_MAX];
    const size_t n = comma ? (size_t)(comma - spec) : 0;
    if (!comma || n == 0 || n >= sizeof link)
        return cmd_fail("--payload '%s': LINK,mass,x,y,z[,Ixx,Iyy,Izz,Ixy,Ixz,Iyz], LINK a link of %s", spec, path);
    memcpy(link, spec, n);
    link[n] = '\0';
    double v[10] = {0.0}; /* mass, x, y, z, Ixx, Iyy, Izz, Ixy, Ixz, Iyz */
    int count = 0;
    for (const char *p = comma + 1;; count++) {
        char *end;
        const double x = strtod(p, &end);
        if (count == 10 || end == p || (*end && *end != ',') || !isfinite(x))
            return cmd_fail("--payload '%s': after the link, 4 or 10 finite numbers separated by commas: mass (kg), "
                            "x, y, z (m), and optionally Ixx, Iyy, Izz, Ixy, Ixz, Iyz (kg m^2)", spec);
        v[count] = x;
        if (!*end) {
            count++;
            break;
        }
        p = end + 1;
    }
    if (count != 4 && count != 10)
        return cmd_fail("--payload '%s': %d numbers after the link; 4 (mass, x, y, z) or 10 (and Ixx, Iyy, Izz, Ixy, "
                        "Ixz, Iyz)", spec, count);
    if (vt_builder_find_frame(b, link) < 0)
        return cmd_fail("--payload '%s': '%s' is not a link of %s", spec, link, path);
    vt_payload_def p = vt_default_payload_def();
    p.frame = link;
    p.mass = v[0];
    memcpy(p.point, v + 1, sizeof p.point);
    const double J[9] = {v[4], v[7], v[8], v[7], v[5], v[9], v[8], v[9], v[6]};
    memcpy(p.inertia, J, sizeof J);
    const int st = vt_builder_add_payload(b, &p);
    if (st < 0) return cmd_fail("--payload '%s': %s", spec, vt_builder_message(b));
    return 0;
}

const char *cmd_joint_kind(int jt)
{
    static const char *const kinds[VT_JOINT_TYPE_COUNT] = {"base",      "revolute",    "universal", "spherical",
                                                           "prismatic", "cylindrical", "floating"};
    return jt >= 0 && jt < VT_JOINT_TYPE_COUNT ? kinds[jt] : "?";
}

const char *cmd_empty_hint(vt_status st, int floating)
{
    return st == VT_ERR_EMPTY_MODEL && !floating
               ? " (every link is fixed to the world; with --floating the root link floats)"
               : "";
}
