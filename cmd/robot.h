/* The command's robot: a URDF file loaded as the command reads it (cmd/robot.c). */
#ifndef VTDYN_CMD_ROBOT_H
#define VTDYN_CMD_ROBOT_H

#include "vtdyn.h"

/* loads the URDF at path into a new builder *b (a root link floats when floating is nonzero; a
 * mimic joint is its own joint); 0, or 1 with the message printed */
int cmd_load_urdf(vt_builder **b, const char *path, int floating);

/* a joint type's name as `info` prints it ("revolute", "floating", ...; "?" out of range) */
const char *cmd_joint_kind(int jt);

/* what to add to the message of a model that could not be built with status st: the way out of
 * an empty model (every link fixed: a one-link robot) when the root was not floating; else "" */
const char *cmd_empty_hint(vt_status st, int floating);

#endif
