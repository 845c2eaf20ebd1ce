//! Cell types, their node counts, local facets and VTK codes.
//!
//! Node numbering follows VTK (identical to Gmsh for every type here except `Tet10`, whose last
//! two mid-edge nodes Gmsh swaps; the Gmsh reader permutes them):
//!
//! ```text
//! Tri3/Tri6      Quad4/Quad8        Tet10 mid-edge nodes: 4:(0,1) 5:(1,2) 6:(2,0)
//!   2              3---6---2                              7:(0,3) 8:(1,3) 9:(2,3)
//!   | \            |       |        Hex8: 0-1-2-3 bottom (counter-clockwise seen from +z),
//!   5   4          7       5              4-5-6-7 top, node i+4 above node i
//!   |     \        |       |
//!   0---3---1      0---4---1        Line3: 0 and 1 the ends, 2 the middle
//! ```
//! Local facets are listed so that their node order gives the **outward** normal: for an edge
//! (a, b) of a counter-clockwise 2D cell the outward normal is (dy, -dx)/|.|; for a 3D face the
//! normal is (x1 - x0) x (x2 - x0) by the right-hand rule. This holds for cells with positive
//! Jacobian (counter-clockwise in 2D, right-handed in 3D); generators and readers produce such cells.

/// The kinds of cells a mesh can hold (volume cells and the facets that bound them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellType {
    /// 2-node line.
    Line2,
    /// 3-node quadratic line (ends, then middle).
    Line3,
    /// 3-node triangle.
    Tri3,
    /// 6-node quadratic triangle.
    Tri6,
    /// 4-node quadrilateral.
    Quad4,
    /// 8-node serendipity quadrilateral.
    Quad8,
    /// 4-node tetrahedron.
    Tet4,
    /// 10-node quadratic tetrahedron.
    Tet10,
    /// 8-node hexahedron.
    Hex8,
}

use CellType::*;

impl CellType {
    /// Number of nodes.
    pub fn num_nodes(self) -> usize {
        match self {
            Line2 => 2,
            Line3 => 3,
            Tri3 => 3,
            Tri6 => 6,
            Quad4 => 4,
            Quad8 => 8,
            Tet4 => 4,
            Tet10 => 10,
            Hex8 => 8,
        }
    }

    /// Number of corner (vertex) nodes; they come first in the node list.
    pub fn num_corners(self) -> usize {
        match self {
            Line2 | Line3 => 2,
            Tri3 | Tri6 => 3,
            Quad4 | Quad8 => 4,
            Tet4 | Tet10 => 4,
            Hex8 => 8,
        }
    }

    /// Topological dimension (1 for lines, 2 for surfaces, 3 for volumes).
    pub fn dim(self) -> usize {
        match self {
            Line2 | Line3 => 1,
            Tri3 | Tri6 | Quad4 | Quad8 => 2,
            Tet4 | Tet10 | Hex8 => 3,
        }
    }

    /// Polynomial order of the geometry / interpolation (1 or 2).
    pub fn order(self) -> usize {
        match self {
            Line3 | Tri6 | Quad8 | Tet10 => 2,
            _ => 1,
        }
    }

    /// The local facets: (facet type, local node indices), ordered for an outward normal.
    pub fn facets(self) -> &'static [(CellType, &'static [usize])] {
        match self {
            Line2 | Line3 => &[],
            Tri3 => &[(Line2, &[0, 1]), (Line2, &[1, 2]), (Line2, &[2, 0])],
            Tri6 => &[
                (Line3, &[0, 1, 3]),
                (Line3, &[1, 2, 4]),
                (Line3, &[2, 0, 5]),
            ],
            Quad4 => &[
                (Line2, &[0, 1]),
                (Line2, &[1, 2]),
                (Line2, &[2, 3]),
                (Line2, &[3, 0]),
            ],
            Quad8 => &[
                (Line3, &[0, 1, 4]),
                (Line3, &[1, 2, 5]),
                (Line3, &[2, 3, 6]),
                (Line3, &[3, 0, 7]),
            ],
            Tet4 => &[
                (Tri3, &[0, 2, 1]),
                (Tri3, &[0, 1, 3]),
                (Tri3, &[0, 3, 2]),
                (Tri3, &[1, 2, 3]),
            ],
            Tet10 => &[
                (Tri6, &[0, 2, 1, 6, 5, 4]),
                (Tri6, &[0, 1, 3, 4, 8, 7]),
                (Tri6, &[0, 3, 2, 7, 9, 6]),
                (Tri6, &[1, 2, 3, 5, 9, 8]),
            ],
            Hex8 => &[
                (Quad4, &[0, 3, 2, 1]),
                (Quad4, &[4, 5, 6, 7]),
                (Quad4, &[0, 1, 5, 4]),
                (Quad4, &[1, 2, 6, 5]),
                (Quad4, &[2, 3, 7, 6]),
                (Quad4, &[3, 0, 4, 7]),
            ],
        }
    }

    /// VTK cell type code.
    pub fn vtk_code(self) -> u8 {
        match self {
            Line2 => 3,
            Line3 => 21,
            Tri3 => 5,
            Tri6 => 22,
            Quad4 => 9,
            Quad8 => 23,
            Tet4 => 10,
            Tet10 => 24,
            Hex8 => 12,
        }
    }

    /// Short upper-case name, as used in messages ("TRI3", "HEX8", ...).
    pub fn name(self) -> &'static str {
        match self {
            Line2 => "LINE2",
            Line3 => "LINE3",
            Tri3 => "TRI3",
            Tri6 => "TRI6",
            Quad4 => "QUAD4",
            Quad8 => "QUAD8",
            Tet4 => "TET4",
            Tet10 => "TET10",
            Hex8 => "HEX8",
        }
    }
}

impl std::fmt::Display for CellType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
