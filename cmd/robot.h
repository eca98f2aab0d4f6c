/* The command's robot: a URDF file loaded as the command reads it (cmd/robot.c). */
#ifndef VTDYN_CMD_ROBOT_H
#define VTDYN_CMD_ROBOT_H

#include "vtdyn.h"

/* loads the URDF at path into a new builder *b (a root link floats when floating is nonzero; a
 * mimic joint is its own joint; the joints' <dynamics> read when dynamics is nonzero; the
 * inertia checks' tolerance inertia_tol, the library's default when negative); 0, or 1 with the
 * message printed */
int cmd_load_urdf(vt_builder **b, const char *path, int floating, int dynamics, double inertia_tol);

/* --joint-params FILE: a CSV file with the header joint,armature,damping,friction (any order) and
 * a row per joint named: its armature, damping and Coulomb friction, all three from the file
 * (replacing the URDF's <dynamics>); 0, or 1 with the message printed */
int cmd_joint_params(vt_builder *b, const char *file, const char *path);

/* --payload LINK,mass,x,y,z[,Ixx,Iyy,Izz,Ixy,Ixz,Iyz]: a rigid body fixed to the link LINK of the
 * robot at path (its centre of mass at x, y, z and its inertia about it in LINK's URDF frame),
 * merged into LINK's body as the loader merges a fixed link; 0, or 1 with the message printed */
int cmd_add_payload(vt_builder *b, const char *spec, const char *path);

/* --contacts FILE: a CSV file with the header frame,mu (any order, optional columns faces,
 * nx,ny,nz, weight, name, x,y,z) and a row per contact: a frame of the model m (a URDF link's
 * name), the point in its axes from its origin (x,y,z; default 0: the origin), Coulomb's μ ≥ 0
 * (empty: bilateral) and the contact's name (default: the frame's); into *defs (n) and *names
 * (malloc'd: the n names, then the n frames, which the defs' name and frame point into); 0, or 1
 * with the message printed */
int cmd_contacts(const vt_model *m, const char *file, vt_contact_def **defs, char (**names)[VT_NAME_MAX], int *n);

/* a joint type's name as `info` prints it ("revolute", "floating", ...; "?" out of range) */
const char *cmd_joint_kind(int jt);

/* what to add to the message of a model that could not be built with status st: the way out of
 * an empty model (every link fixed: a one-link robot) when the root was not floating; else "" */
const char *cmd_empty_hint(vt_status st, int floating);

#endif
