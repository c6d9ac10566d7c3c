"""A perfect mirror against an independent renderer (issue 39 item 3): the room of
Data/scenes/mirror_room.scene (its wall x = 3 a mirror of reflectance 1) rendered by
`sphcover render` at the filters' defaults (the scene has no settings block), 256 x 256, 16 spp,
is the same picture as the room unfolded across the mirror plane, all diffuse
(Data/scenes/mirror_room_unfolded.scene, Data/scenes/tools/nondiffuse_rooms.py says why),
path traced by Blender Cycles in Data/reference/mirror_room_unfolded_cycles.exr (256 x 256,
2048 spp in 4 passes, block noise 0.06 % at 16 x 16 blocks; Data/reference/README.md,
"Non-diffuse references"). The mirror is never given to Cycles: its sharp glossy came out 14 %
dark as a mirror. Compared by the issue-16 metric of Testing/Benchmarks/time_to_accuracy.py
(the relative RMS of luminance block means on a 16 x 16 and a 64 x 64 grid) and the image's
mean luminance.

Measured 2026-12-07: 5.13 % and 9.43 %, mean luminance -0.05 % (mirror pixels 7.7 % / 14.3 %,
the rest 2.0 % / 4.5 %; the unfolded room by sphcover itself 0.62 % / 1.17 %). The limits,
6.5 % / 11.5 % and 1 %, keep only a margin above that: the mirror's image is the open question
of issue 39 item 3 (a 64 x 256 hemisphere grid did not reduce it: 5.33 % / 9.72 %), so this
test pins today's figure rather than endorsing it. WIP: the mutation check (mirror reflectance
0.9) has not been run yet."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_reference_check import check_against_cycles  # noqa: E402

check_against_cycles("mirror_room.scene", "mirror_room_unfolded_cycles.exr", 0.065, 0.115, 0.01)
