// A standing figure for the scaffold corpus (mm, Z up, 50 mm tall): two legs,
// a torso, arms held out and down at 30 deg below horizontal with mitten
// hands, a head on a neck (the chin overhangs the neck) and a hat brim.
$fn = 32;
// legs
for (x = [-5, 5]) translate([x, 0, 0]) cylinder(d1 = 7, d2 = 8, h = 20);
// torso
translate([0, 0, 19]) scale([1, 0.6, 1]) cylinder(d1 = 20, d2 = 24, h = 16);
// arms: from the shoulders, 20 mm long, tipped 30 deg below horizontal
for (s = [-1, 1]) translate([s * 11, 0, 33]) rotate([0, s * 120, 0]) {
    cylinder(d = 5, h = 20);
    translate([0, 0, 20]) sphere(d = 7);
}
// neck and head; the chin is the underside of the head sphere
translate([0, 0, 34]) cylinder(d = 6, h = 4);
translate([0, 0, 43]) scale([0.9, 1, 1]) sphere(d = 12);
// nose
translate([0, -5.5, 43]) rotate([90, 0, 0]) cylinder(d1 = 3, d2 = 1.5, h = 2.5);
// hat: brim and crown
translate([0, 0, 47]) cylinder(d = 18, h = 1);
translate([0, 0, 47.5]) cylinder(d = 9, h = 2.5);
