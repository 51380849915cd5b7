/* SPDX-License-Identifier: MIT */
/* The plain-C API of supermodal (C99 or later; also compiles as C++). Opaque handles, Def structs with
 * default functions, every call returns an sm_status. Guide and ownership rules: docs/c_api.md.
 * The C++ API is supermodal/supermodal.hpp.
 *
 * Conventions
 * - Units are SI: metres, seconds, kilograms, newtons, radians. The world is Y-up.
 * - Every function that can fail returns an sm_status; on failure sm_last_error() says why (naming the
 *   file and the JSON pointer for scene errors) and outputs are left unchanged unless stated.
 * - NULL worlds, null or stale body handles, NULL required pointers and non-finite numbers are refused
 *   with an error code; nothing in this API aborts on such input. (A world pointer used after
 *   sm_world_destroy() is undefined behaviour, as with free(); it is caught only sometimes.)
 * - The caller owns what it creates (sm_world, sm_snapshot) and frees it with the matching destroy
 *   function. Strings passed in are copied; strings returned stay valid as documented per function.
 * - A world is not thread-safe: use one world from one thread at a time. Different worlds may run on
 *   different threads; sm_last_error() is per thread. */
#ifndef SUPERMODAL_SUPERMODAL_H
#define SUPERMODAL_SUPERMODAL_H

#include "supermodal/api.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Status and errors ------------------------------------------------------------------------------ */

typedef enum sm_status {
    SM_OK = 0,
    SM_ERROR_NULL_ARGUMENT = 1,     /* A required pointer (world, out-param, string) was NULL. */
    SM_ERROR_INVALID_HANDLE = 2,    /* A NULL world, or a body handle that is null or stale. */
    SM_ERROR_INVALID_ARGUMENT = 3,  /* A non-finite number, or a value out of its documented range. */
    SM_ERROR_SCENE = 4,             /* Scene file or JSON unreadable or invalid (message names where). */
    SM_ERROR_NOT_FOUND = 5,         /* No body of that name. */
    SM_ERROR_BUFFER_TOO_SMALL = 6,  /* The caller's buffer is shorter than the result; count says how long. */
    SM_ERROR_SNAPSHOT_MISMATCH = 7, /* The snapshot does not fit this world (bodies created/destroyed). */
    SM_ERROR_INTERNAL = 8,          /* An unexpected failure inside the engine (e.g. out of memory). */
    SM_STATUS_MAX_ENUM = 0x7FFFFFFF /* Not a status: keeps the enum 32-bit so any int is a valid value. */
} sm_status;

/* Constant name of a status ("SM_ERROR_SCENE"); "SM_UNKNOWN_STATUS" for values outside the enum. */
SM_API const char* sm_status_string(sm_status status);
/* Message of the last call on this thread: "" after a success, else what failed and where, e.g.
 * "<string>: /bodies/1/shape/radii/0: expected a number > 0, found -1". Valid until the next call of this
 * API on the same thread; copy it to keep it. */
SM_API const char* sm_last_error(void);

/* ---- Version ---------------------------------------------------------------------------------------- */

/* The library's version, "MAJOR.MINOR.PATCH" (a static string; never fails, leaves sm_last_error()
 * alone). supermodal/version.h has the headers' version as macros: SM_VERSION_STRING, SM_VERSION_MAJOR. */
SM_API const char* sm_version(void);

/* ---- Plain data ------------------------------------------------------------------------------------- */

typedef struct sm_vec3 {
    double x, y, z;
} sm_vec3;

/* Unit quaternion [w, x, y, z]; as orientation it rotates body frame to world frame. */
typedef struct sm_quat {
    double w, x, y, z;
} sm_quat;

/* A body of a world. Stable for the body's life: (generation << 32) | slot index. 0 is the null body; a
 * destroyed body's handle is never reused for another body (its slot's generation moves on). Handles do
 * not record their world: use one only with the world that made it. */
typedef struct sm_body {
    uint64_t id;
} sm_body;

typedef struct sm_world sm_world;       /* Opaque; sm_world_destroy() frees it. */
typedef struct sm_snapshot sm_snapshot; /* Opaque; sm_snapshot_destroy() frees it. */

/* ---- Worlds ----------------------------------------------------------------------------------------- */

/* How to make an empty world. Start from sm_world_def_default() and change what differs. Contact
 * settings keep the engine's defaults (docs/contact.md); scenes set them through their JSON. */
typedef struct sm_world_def {
    double dt;                 /* Fixed step [s], finite, > 0. Default 0.002. */
    int substep_count;         /* Substeps per step, in [1, 1000]. Default 1. */
    sm_vec3 gravity;           /* [m/s^2], world frame. Default (0, -9.81, 0). */
    int max_steps_per_advance; /* sm_world_advance() runs at most this many steps, >= 1. Default 64. */
    int constraint_iterations; /* Constraint passes per substep, in [1, 100]. Default 4. */
    int thread_count;          /* Threads for the step, in [1, 64]; results are bit-identical for any. */
    int split_islands;         /* Nonzero: islands of >= 1024 rows are solved in slabs the threads share
                                * (bit-identical for any thread count, not to a run without). Default 0. */
} sm_world_def;

SM_API sm_world_def sm_world_def_default(void);

/* Makes an empty world. *out_world receives it on success. */
SM_API sm_status sm_world_create(const sm_world_def* def, sm_world** out_world);
/* Loads a scene file (docs/scene_format.md) and builds its world. Errors (SM_ERROR_SCENE) name the file
 * and the JSON pointer of the bad value. */
SM_API sm_status sm_world_create_from_file(const char* path, sm_world** out_world);
/* As sm_world_create_from_file, from NUL-terminated scene JSON text; errors name "<string>". Includes in
 * the text resolve against the current directory. */
SM_API sm_status sm_world_create_from_json(const char* json, sm_world** out_world);
/* Frees a world; NULL is ignored. Its body handles become meaningless; snapshots stay valid to free. */
SM_API void sm_world_destroy(sm_world* world);

/* The settings in force. */
SM_API sm_status sm_world_get_def(const sm_world* world, sm_world_def* out_def);
/* Changes settings between steps. thread_count cannot change; dt can change only before the first step
 * (the world's time is step_count * dt). Checked as at creation; on failure nothing changes. */
SM_API sm_status sm_world_set_def(sm_world* world, const sm_world_def* def);
/* Changes gravity [m/s^2], world frame, from the next step on. */
SM_API sm_status sm_world_set_gravity(sm_world* world, sm_vec3 gravity);

/* Runs one fixed step of dt. */
SM_API sm_status sm_world_step(sm_world* world);
/* Adds seconds [s] (finite, >= 0) of real time and runs the whole steps it makes up (at most
 * max_steps_per_advance; the rest of a backlog is dropped). *out_steps (may be NULL) gets the count. */
SM_API sm_status sm_world_advance(sm_world* world, double seconds, int* out_steps);
/* Fraction [0, 1) of a step left over by sm_world_advance(): blend previous and current poses by it
 * (sm_body_get_interpolated_pose does). */
SM_API sm_status sm_world_get_interpolation_alpha(const sm_world* world, double* out_alpha);
SM_API sm_status sm_world_get_time(const sm_world* world, double* out_seconds); /* Simulated time [s]. */
SM_API sm_status sm_world_get_step_count(const sm_world* world, uint64_t* out_steps);
/* FNV-1a hash of the whole dynamic state: same scene, same build, same calls -> same hash. */
SM_API sm_status sm_world_get_state_hash(const sm_world* world, uint64_t* out_hash);

/* ---- Snapshots -------------------------------------------------------------------------------------- */

/* Copies the world's dynamic state (poses, velocities, contact caches, modal amplitudes, time). */
SM_API sm_status sm_world_snapshot(const sm_world* world, sm_snapshot** out_snapshot);
/* Puts a snapshot's state back: the world then steps bit-identically to the one it came from.
 * SM_ERROR_SNAPSHOT_MISMATCH if bodies or constraints were created or destroyed since. */
SM_API sm_status sm_world_restore(sm_world* world, const sm_snapshot* snapshot);
/* Frees a snapshot; NULL is ignored. Independent of the world it came from. */
SM_API void sm_snapshot_destroy(sm_snapshot* snapshot);

/* ---- Bodies ----------------------------------------------------------------------------------------- */

typedef enum sm_motion {
    SM_MOTION_STATIC = 0,    /* Never moves; infinite mass. */
    SM_MOTION_KINEMATIC = 1, /* Moves with its set velocity; forces ignored. */
    SM_MOTION_DYNAMIC = 2    /* Moves under forces. */
} sm_motion;

typedef enum sm_shape_type {
    SM_SHAPE_SUPERQUADRIC = 0, /* Barr superquadric: radii along x, y, z; z is the polar axis. */
    SM_SHAPE_PLANE = 1         /* Half-space {p : normal . p <= offset}; static bodies only. */
} sm_shape_type;

/* How to make a body. Start from sm_body_def_default() (a dynamic water-density sphere of radius
 * 0.5 m at the origin) and change what differs. */
typedef struct sm_body_def {
    const char* name; /* Copied; NULL or "" for none. Unique names are found by sm_world_find_body(). */
    sm_motion motion;
    sm_shape_type shape;
    sm_vec3 radii;            /* Superquadric radii [m], each finite and > 0. */
    double epsilon1;          /* Superquadric north-south exponent, in (0, 4]; 1 = round, -> 0 = box. */
    double epsilon2;          /* Superquadric east-west exponent, in (0, 4]. */
    sm_vec3 plane_normal;     /* Plane outward normal, world frame, non-zero. */
    double plane_offset;      /* Plane offset along the normal [m]. */
    double density;           /* [kg/m^3], finite; > 0 for dynamic bodies (the only ones it moves). */
    sm_vec3 position;         /* Shape origin [m], world frame. */
    sm_quat orientation;      /* Body to world rotation, non-zero (normalised on use). */
    sm_vec3 linear_velocity;  /* Of the centre of mass [m/s], world frame. */
    sm_vec3 angular_velocity; /* [rad/s], world frame. */
    double gravity_scale;     /* Multiplies the world's gravity [-]. */
    double friction;          /* Coulomb coefficient [-], >= 0. */
    double restitution;       /* [-], in [0, 1]. */
    int modal_mode_count;     /* 0: rigid. 1..256: deforms through this many vibration modes (dynamic
                                 superquadrics only; lattice chosen from the aspect ratio). */
    double young;             /* Young's modulus [Pa], > 0: the modes' stiffness and material contact. */
    double poisson;           /* Poisson's ratio [-], in (-1, 0.5). */
    double damping_ratio;     /* Modal: damping ratio of every mode [-], >= 0. */
} sm_body_def;

SM_API sm_body_def sm_body_def_default(void);

/* Creates a body. Invalid defs (and modal bases that cannot be built) are refused with a message. */
SM_API sm_status sm_world_create_body(sm_world* world, const sm_body_def* def, sm_body* out_body);
/* Destroys a body; its handle becomes stale (later calls with it return SM_ERROR_INVALID_HANDLE). */
SM_API sm_status sm_world_destroy_body(sm_world* world, sm_body body);
/* The body with this name; SM_ERROR_NOT_FOUND if none. */
SM_API sm_status sm_world_find_body(const sm_world* world, const char* name, sm_body* out_body);
/* Number of live bodies. */
SM_API sm_status sm_world_get_body_count(const sm_world* world, size_t* out_count);
/* Live bodies in creation (entity-index) order, the order of hashes and scene files. *out_count gets the
 * total. Buffers, here and below: NULL with capacity 0 is a size query (SM_OK); a buffer shorter than the
 * result gets its first `capacity` entries and SM_ERROR_BUFFER_TOO_SMALL. */
SM_API sm_status sm_world_get_bodies(const sm_world* world, sm_body* bodies, size_t capacity,
                                     size_t* out_count);
/* 1 if body is a live body of world, else 0 (also for a NULL world). Never sets an error. */
SM_API int sm_body_is_valid(const sm_world* world, sm_body body);

/* The body's name, NUL-terminated, into buffer (capacity bytes). *out_length (may be NULL) gets its
 * length without the NUL. SM_ERROR_BUFFER_TOO_SMALL if it does not fit (buffer then holds a truncated,
 * terminated copy). NULL with capacity 0 is a size query. */
SM_API sm_status sm_body_get_name(const sm_world* world, sm_body body, char* buffer, size_t capacity,
                                  size_t* out_length);
SM_API sm_status sm_body_get_motion(const sm_world* world, sm_body body, sm_motion* out_motion);
/* Mass [kg] from shape and density; reported for static and kinematic bodies too (which move as if
 * infinitely heavy); 0 for planes. */
SM_API sm_status sm_body_get_mass(const sm_world* world, sm_body body, double* out_mass);
/* Shape origin [m] and orientation (body to world), world frame, after the last step. */
SM_API sm_status sm_body_get_pose(const sm_world* world, sm_body body, sm_vec3* out_position,
                                  sm_quat* out_orientation);
/* The pose blended between the last two steps by the interpolation alpha, for rendering. */
SM_API sm_status sm_body_get_interpolated_pose(const sm_world* world, sm_body body, sm_vec3* out_position,
                                               sm_quat* out_orientation);
/* Centre-of-mass velocity [m/s] and angular velocity [rad/s], world frame. */
SM_API sm_status sm_body_get_velocity(const sm_world* world, sm_body body, sm_vec3* out_linear,
                                      sm_vec3* out_angular);

/* Teleports the shape origin [m] (no interpolation across the jump). */
SM_API sm_status sm_body_set_position(sm_world* world, sm_body body, sm_vec3 position);
/* Turns the body about its shape origin; non-zero, normalised here. */
SM_API sm_status sm_body_set_orientation(sm_world* world, sm_body body, sm_quat orientation);
/* Sets velocities [m/s], [rad/s], world frame; static bodies keep zero. */
SM_API sm_status sm_body_set_velocity(sm_world* world, sm_body body, sm_vec3 linear, sm_vec3 angular);

/* Forces last for the next step only; non-dynamic bodies ignore them (SM_OK). */
/* Force [N] at a world point [m]: also a torque about the centre of mass, and on a modal body a load
 * on its modes. */
SM_API sm_status sm_body_apply_force(sm_world* world, sm_body body, sm_vec3 force, sm_vec3 point);
/* Force [N] through the centre of mass, like gravity (does not deform a modal body). */
SM_API sm_status sm_body_apply_force_at_center(sm_world* world, sm_body body, sm_vec3 force);
SM_API sm_status sm_body_apply_torque(sm_world* world, sm_body body,
                                      sm_vec3 torque); /* [N m], world frame. */
/* Impulse [N s] at a world point [m]: changes velocities at once (and a modal body's mode rates). */
SM_API sm_status sm_body_apply_impulse(sm_world* world, sm_body body, sm_vec3 impulse, sm_vec3 point);
/* Angular impulse [N m s], world frame. */
SM_API sm_status sm_body_apply_angular_impulse(sm_world* world, sm_body body, sm_vec3 impulse);

/* ---- Deformation ------------------------------------------------------------------------------------ */

/* Where material points are now [m], world frame: for each rest point (shape frame [m], the frame of
 * sm_body_def's radii) the rigid pose plus the modal displacement; rigid bodies just the pose.
 * rest_points and out_points hold count entries each (may be NULL when count is 0). */
SM_API sm_status sm_body_get_deformed_points(const sm_world* world, sm_body body, const sm_vec3* rest_points,
                                             size_t count, sm_vec3* out_points);
/* The body's surface as a triangle mesh, deformed and in world frame [m]: `resolution` segments around the
 * equator (clamped to [4, 2048]), three indices per triangle, counter-clockwise seen from outside.
 * *out_vertex_count and *out_index_count get the sizes; both buffers NULL with capacity 0 is a size
 * query. SM_ERROR_BUFFER_TOO_SMALL if either capacity is short (nothing written). The same resolution
 * gives the same sizes and indices every call (the rest mesh is deformed, not re-meshed). Planes have
 * no mesh (0, 0). The first call per body and resolution tessellates and caches the rest mesh (memory
 * until the body or world is destroyed); later calls only deform it, cost linear in the vertex count. */
SM_API sm_status sm_body_get_mesh(const sm_world* world, sm_body body, int resolution, sm_vec3* positions,
                                  size_t vertex_capacity, uint32_t* indices, size_t index_capacity,
                                  size_t* out_vertex_count, size_t* out_index_count);
/* A modal body's amplitudes q [sqrt(kg) m] (0 entries for a rigid body). Buffer rules as
 * sm_world_get_bodies. */
SM_API sm_status sm_body_get_modal_amplitudes(const sm_world* world, sm_body body, double* amplitudes,
                                              size_t capacity, size_t* out_count);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* SUPERMODAL_SUPERMODAL_H */
