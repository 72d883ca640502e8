// A block with a horizontal shelf: needs support under the shelf.
cube([10, 10, 12]);
translate([10, 0, 9]) cube([12, 10, 3]);
