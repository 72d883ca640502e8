// A bust for the scaffold corpus (mm, Z up, 45 mm tall): shoulders and chest
// cut flat at the bottom, a neck, and an egg-shaped head whose chin and jaw
// overhang the neck, with a nose, brow, ears and a hair bun at the back.
$fn = 48;
// shoulders and chest: the upper half of a flattened ellipsoid
intersection() {
    scale([22, 11, 16]) sphere(r = 1);
    translate([-30, -30, 0]) cube([60, 60, 30]);
}
// neck
translate([0, 0, 12]) cylinder(d = 10, h = 14);
// head: egg, chin forward (-y) and down
translate([0, -1, 32]) scale([8.5, 10, 11.5]) sphere(r = 1);
// jaw and chin
hull() {
    translate([0, -6, 24.5]) sphere(r = 2.5);
    translate([0, 0, 27]) scale([6.5, 5, 3]) sphere(r = 1);
}
// nose and brow
translate([0, -10.5, 33]) rotate([80, 0, 0]) cylinder(d1 = 3.5, d2 = 1.5, h = 3);
translate([0, -9.5, 36]) scale([6, 2, 1.2]) sphere(r = 1);
// ears
for (s = [-1, 1]) translate([s * 8.5, 0, 32]) scale([1.2, 2.5, 3.5]) sphere(r = 1);
// hair bun
translate([0, 8.5, 37]) sphere(r = 4.5);
