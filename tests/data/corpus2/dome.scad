// A hollow shell for the scaffold corpus (mm, Z up, 30 mm tall): a
// hemispherical dome 60 mm across with 2 mm walls, open at the bottom and
// standing on its rim, with a round 12 mm window in the side. The whole
// inside is a ceiling.
$fn = 96;
difference() {
    intersection() {
        sphere(r = 30);
        translate([-30, -30, 0]) cube([60, 60, 30]);
    }
    sphere(r = 28);
    translate([0, 0, 10]) rotate([90, 0, 0]) cylinder(d = 12, h = 40);
}
