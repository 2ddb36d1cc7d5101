// tests/embed/hash.cpp — tether from C++ through the installed headers and
// library only (tests/embed/install.sh builds it with pkg-config): a chain
// of particles on springs falls onto a box for 120 steps; prints the hash
// for the script to compare with a constant.
#include <tether.h>

#include <cstdio>

int main()
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    if (w == nullptr) return 1;
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_def box = tt_shape_def_default();
    box.type = TT_SHAPE_BOX;
    box.position = tt_vec2{ 0.0, -1.0 };
    box.half_extents = tt_vec2{ 5.0, 0.5 };
    tt_shape_create(w, &box);
    tt_particle prev{};
    for (int i = 0; i < 10; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = tt_vec2{ 0.4 * i, 3.0 };
        pd.radius = 0.15;
        tt_particle p = tt_particle_create(w, &pd);
        if (i > 0) {
            tt_spring_def sd = tt_spring_def_default();
            sd.a = prev;
            sd.b = p;
            sd.stiffness = 200;
            tt_spring_create(w, &sd);
        }
        prev = p;
    }
    for (int s = 0; s < 120; s++)
        if (tt_world_step(w, 1.0 / 60) != TT_OK) {
            std::printf("step failed: %s\n", tt_last_error(w));
            return 1;
        }
    std::printf("hash %016llx\n", static_cast<unsigned long long>(tt_world_hash(w)));
    tt_world_destroy(w);
    return 0;
}
