* Hand-made MIQP exercising RANGES on G, L and E rows, negative lower bounds,
* a general integer, an MI bound and a column that appears only in the objective.
*   min 0.5*(n - 2.6)^2 + 0.5*(w - 1)^2 + 0.5*(v - 1)^2 - 0.5 b
*   s.t. r1 (G, rhs 1, range 1.5):   1 <= n + w      <= 2.5
*        r2 (L, rhs 1, range 4):    -3 <= n - w + 4b <= 1
*        r3 (E, rhs 0, range -1):   -1 <= w - 2b     <= 0
*        n integer in [-5, 5], w in [-2, 3], v in (-inf, 0.5] (MI), b binary
* The constants 0.5*2.6^2 + 0.5 + 0.5 = 4.38 are left out of the file.
* By hand:
*   v is alone: v = 0.5 costs 0.125.
*   b = 0: r3 gives w in [-1, 0]; r2 gives n <= 1 + w <= 1; r1 gives n >= 1 - w >= 1;
*          so n = 1, w = 0, cost 0.5*1.6^2 + 0.5*1^2 = 1.78.
*   b = 1: r3 gives w in [1, 2]; r2 gives n <= w - 3 <= -1; r1 gives n >= 1 - w >= -1;
*          so n = -1, w = 2, cost 0.5*3.6^2 + 0.5 - 0.5 = 6.48.
*   optimum: b = 0, n = 1, w = 0, v = 0.5; full objective 1.905,
*            MPS objective 1.905 - 4.38 = -2.475.
* A reader that took the E row's negative range as [0, 1] would find w = 1 and 1.405 - 4.38.
NAME ranges_bounds
ROWS
 N obj
 G r1
 L r2
 E r3
COLUMNS
 MARKER 'MARKER' 'INTORG'
 n obj -2.6 r1 1
 n r2 1
 MARKER 'MARKER' 'INTEND'
 w obj -1 r1 1
 w r2 -1 r3 1
 v obj -1
 MARKER 'MARKER' 'INTORG'
 b obj -0.5 r2 4
 b r3 -2
 MARKER 'MARKER' 'INTEND'
RHS
 rhs r1 1 r2 1
RANGES
 rng r1 1.5 r2 4
 rng r3 -1
BOUNDS
 LO bnd n -5
 UP bnd n 5
 LO bnd w -2
 UP bnd w 3
 MI bnd v
 UP bnd v 0.5
 BV bnd b
QUADOBJ
 n n 1
 w w 1
 v v 1
ENDATA
