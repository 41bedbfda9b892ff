* Hand-made MIQP with an off-diagonal quadratic term, listed once (upper triangle).
*   min x^2 + x*y + y^2 - 3x - 3y - 1.5 b1 - 0.2 b2
*       (= 0.5 [x y] Q [x y]' with Q = [[2, 1], [1, 2]]; QUADOBJ lists Q_xx, Q_xy, Q_yy)
*   s.t. e1: x - y + 2 b1 - 2 b2 = 0
*        c1: b1 + b2 <= 1
*        x, y free (FR), b1, b2 binary
* By hand, per assignment of (b1, b2):
*   (0,0): x = y, min 3x^2 - 6x at x = 1: -3
*   (1,0): x = y - 2, min 3y^2 - 12y + 10 at y = 2: -2, plus -1.5: -3.5
*   (0,1): x = y + 2, by symmetry -2, plus -0.2: -2.2
*   (1,1): cut off by c1
*   optimum -3.5 at x = 0, y = 2, b1 = 1, b2 = 0 (no constant term).
* A reader that took Q_xy as 0.5 would report -3.6; one that doubled it, -3.75.
NAME offdiag_upper
ROWS
 N obj
 E e1
 L c1
COLUMNS
 x obj -3 e1 1
 y obj -3 e1 -1
 MARKER 'MARKER' 'INTORG'
 b1 obj -1.5 e1 2
 b1 c1 1
 b2 obj -0.2 e1 -2
 b2 c1 1
 MARKER 'MARKER' 'INTEND'
RHS
 rhs c1 1
BOUNDS
 FR bnd x
 FR bnd y
 UP bnd b1 1
 UP bnd b2 1
QUADOBJ
 x x 2
 x y 1
 y y 2
ENDATA
