// A large flat overhang high up, for the scaffold corpus (mm, Z up, 45 mm
// tall): a 10 x 10 mm post on a 24 x 24 mm foot, carrying a 50 x 40 x 3 mm
// flat plate at z 42-45, off centre so one side reaches 30 mm out; a
// 45-degree gusset under the short side.
cube([24, 24, 2]);
translate([7, 7, 0]) cube([10, 10, 42]);
translate([-3, -8, 42]) cube([50, 40, 3]);
// gusset: a 45-degree wedge under the plate on the -x side of the post
translate([7, 7, 42]) rotate([-90, 0, 0]) linear_extrude(10)
    polygon([[0, 0], [-8, 0], [0, 8]]);
