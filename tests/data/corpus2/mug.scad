// A mug for the scaffold corpus (mm, Z up, 40 mm tall): a 36 mm cylinder,
// 2 mm walls, 2 mm floor, and a D-shaped handle: its lower arm's flat
// underside (z 6) juts 14 mm out of the wall (what a slicer supports), its
// upper arm bridges from the wall to the handle's upright.
$fn = 96;
difference() {
    cylinder(d = 36, h = 40);
    translate([0, 0, 2]) cylinder(d = 32, h = 40);
}
translate([17, -4, 0]) difference() {
    translate([0, 0, 6]) cube([14, 8, 28]);
    translate([0, -1, 11]) cube([9, 10, 18]);
}
