// A dog for the scaffold corpus (mm, Z up, 40 mm tall): a long belly on four
// legs, a neck, a head with a snout whose chin overhangs, drooping ears and a
// tail held out behind.
$fn = 40;
// legs
for (x = [-14, 14], y = [-6, 6]) translate([x, y, 0]) cylinder(d1 = 6, d2 = 7, h = 17);
// body: the belly is its underside, 14 mm above the bed
translate([0, 0, 22]) scale([22, 9, 8]) sphere(r = 1);
// neck, leaning forward
hull() {
    translate([16, 0, 24]) sphere(r = 5);
    translate([22, 0, 32]) sphere(r = 4);
}
// head and snout; the chin is the snout's underside
translate([24, 0, 34]) scale([6, 5, 5]) sphere(r = 1);
hull() {
    translate([27, 0, 33]) sphere(r = 3.5);
    translate([34, 0, 32]) sphere(r = 2.5);
}
// ears
for (s = [-1, 1]) translate([22, s * 5, 34]) rotate([s * 20, 0, 0]) scale([2, 1, 4]) sphere(r = 1);
// tail
translate([-18, 0, 25]) rotate([0, -60, 0]) cylinder(d1 = 3, d2 = 1.5, h = 14);
