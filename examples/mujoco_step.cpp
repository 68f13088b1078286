// SPDX-License-Identifier: MIT
// Steps an MJCF model with impulse::mujoco::step in place of mj_step, the way a MuJoCo program
// would: mjData holds the state, so MuJoCo's rendering, recording and sensors see the result.
//
//   impulse_example_mujoco_step [MODEL.xml] [SECONDS]
#include <impulse/mujoco/mujoco.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
    const std::string path = argc > 1 ? argv[1] : IMPULSE_EXAMPLE_MODEL;
    const double seconds = argc > 2 ? std::atof(argv[2]) : 2.0;
    try
    {
        const impulse::mujoco::ModelPtr model = impulse::mujoco::loadModel(path);
        const impulse::mujoco::DataPtr data(mj_makeData(model.get()));
        mj_forward(model.get(), data.get());

        std::printf("%8s", "t");
        for (int b = 1; b < model->nbody; ++b)
        {
            const char* name = mj_id2name(model.get(), mjOBJ_BODY, b);
            std::printf("  %24s", name != nullptr ? name : "?");
        }
        std::printf("\n");
        const int steps = static_cast<int>(seconds / model->opt.timestep + 0.5);
        for (int k = 0; k <= steps; ++k)
        {
            if (k % 250 == 0)
            {
                // xpos is MuJoCo's own forward kinematics of the qpos the stepper wrote
                std::printf("%8.3f", data->time);
                for (int b = 1; b < model->nbody; ++b)
                {
                    const mjtNum* x = data->xpos + 3 * b;
                    std::printf("  (%6.3f, %6.3f, %6.3f)", x[0], x[1], x[2]);
                }
                std::printf("\n");
            }
            if (k < steps)
            {
                impulse::mujoco::step(model.get(), data.get()); // in place of mj_step(model, data)
            }
        }
        impulse::mujoco::forget(model.get(), data.get()); // before the model and data go
    }
    catch (const impulse::mujoco::ModelError& error)
    {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
    return 0;
}
