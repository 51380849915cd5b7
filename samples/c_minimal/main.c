/* SPDX-License-Identifier: MIT */
/* The smallest C host: load a scene, run one simulated second at 60 frames per second, print each
 * body's pose and the state hash, and show what an error looks like. Plain C11; links the engine. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <supermodal/supermodal.h>

/* Prints the failed call and its message, and leaves main with exit status 2 (bad input) or 1. */
#define CHECK(call)                                                                                          \
    do {                                                                                                     \
        sm_status status_ = (call);                                                                          \
        if (status_ != SM_OK) {                                                                              \
            fprintf(stderr, "%s failed: %s: %s\n", #call, sm_status_string(status_), sm_last_error());       \
            return status_ == SM_ERROR_SCENE ? 2 : 1;                                                        \
        }                                                                                                    \
    } while (0)

int main(int argc, char** argv)
{
    sm_world* world = NULL;
    sm_body bodies[16];
    size_t count = 0;
    size_t i;
    int frame;
    uint64_t steps = 0, hash = 0;

    if (argc != 2) {
        fprintf(stderr, "usage: c_minimal SCENE.json\n");
        return 2;
    }
    CHECK(sm_world_create_from_file(argv[1], &world));

    /* A host's frame loop: the world runs whole fixed steps from its accumulator. */
    for (frame = 0; frame < 60; ++frame)
        CHECK(sm_world_advance(world, 1.0 / 60.0, NULL));

    CHECK(sm_world_get_bodies(world, bodies, sizeof bodies / sizeof bodies[0], &count));
    for (i = 0; i < count; ++i) {
        char name[64];
        sm_vec3 p;
        sm_quat q;
        CHECK(sm_body_get_name(world, bodies[i], name, sizeof name, NULL));
        CHECK(sm_body_get_pose(world, bodies[i], &p, &q));
        printf("%s position %.6f %.6f %.6f orientation %.6f %.6f %.6f %.6f\n", name, p.x, p.y, p.z, q.w, q.x,
               q.y, q.z);
    }
    CHECK(sm_world_get_step_count(world, &steps));
    CHECK(sm_world_get_state_hash(world, &hash));
    printf("steps %" PRIu64 " hash %016" PRIx64 "\n", steps, hash);
    sm_world_destroy(world);

    /* Errors come back as a status plus a message that names the JSON pointer of the bad value. */
    world = NULL;
    if (sm_world_create_from_json(
            "{ \"bodies\": [ { \"name\": \"b\", \"shape\": { \"type\": \"superquadric\", "
            "\"radii\": [0.1, -2, 0.1] } } ] }",
            &world) == SM_ERROR_SCENE)
        printf("bad scene refused: %s\n", sm_last_error());
    else {
        fprintf(stderr, "a bad scene was accepted\n");
        sm_world_destroy(world);
        return 1;
    }
    return EXIT_SUCCESS;
}
