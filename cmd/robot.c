/* The command's robot: the URDF loaded with the command's options, and the joint types' names. */
#include "robot.h"

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
