#!/usr/bin/env python3
# -*- coding: utf-8 -*-
"""
batchelor_green.py -- independent reference for the relative trajectory of two
equal, force-free, torque-free, smooth rigid spheres in unbounded simple shear
u = gdot * y * e_x (Stokes flow), following Batchelor & Green (1972),
J. Fluid Mech. 56, 375-400 ("The hydrodynamic interaction of two small
freely-moving spheres in a linear flow field").

Standard library only (no numpy).  Run:  python3 batchelor_green.py
Lengths are in units of the sphere radius a; r = centre distance / a (contact
at r = 2), xi = r - 2, time in units of 1/gdot.

------------------------------------------------------------------------------
EQUATIONS (re-derived; see doc/lubrication.md):
  relative velocity (BG 1972):  V = Omega x r + E.r - [A rr/r^2 + B (I - rr/r^2)].E.r
  shear plane, r = r (cos th, sin th):
      dr/dt  = gdot r (1 - A(r)) sin th cos th
      dth/dt = -gdot [ sin^2 th + (B(r)/2) cos 2th ]
  (same form as eq. (4.25) at St = 0 in the thesis chapter stored at
   https://123dok.com/id/article/relative-plane-trajectories-spheres-simple-shear-flowshear-flow.10413626 ;
   and re-derived by hand: E.r = (gdot r/2)(sin th, cos th), Omega x r = (gdot/2)(y,-x).)
  First integral (s = sin^2 th):  ds/dr = -[2 s (1-B) + B] / [r (1-A)]
      q(r) = r^2 exp( - int_r^inf 2(A-B)/(rho (1-A)) drho )
      J(r) = int_r^inf q(rho) B(rho) / (rho (1-A(rho))) drho
      q(r) s(r) - J(r) = y_inf^2   (y_inf = upstream offset, since q ~ r^2)
  => closest approach (th = pi/2, s = 1):   q(r_min) - J(r_min) = y_inf^2.

------------------------------------------------------------------------------
HOW A(r), B(r) ARE OBTAINED (equal spheres, lambda = 1):
 A and B are expressed through the two-sphere resistance scalars of Jeffrey &
 Onishi (1984) / Jeffrey (1992), in the Kim & Karrila nondimensionalisation
 (A-type x 6 pi mu a, B,G-type x 4 pi mu a^2, C,H-type x 8 pi mu a^3), with
 d pointing from sphere 1 to sphere 2 and the lambda=1 symmetries
 X^G_21 = -X^G_12, Y^B_21 = -Y^B_12, Y^G_21 = -Y^G_12, Y^H_21 = +Y^H_12.
 Force/torque balance on sphere 1 (derived for fidus, no literature source
 quoted for the final combination):
   radial:        A = (4/3) (XG11 - XG12) / [ r (XA11 - XA12) ]
   perpendicular: B = 8 (YGm + YBm*YHp/YCp) / ( r [3 YAm - YBm^2/YCp] )
       YAm = YA11-YA12, YBm = YB11-YB12, YGm = YG11-YG12,
       YCp = YC11+YC12, YHp = YH11+YH12.
 Validation of these formulas (checked when the script was written): (i) large-r expansion gives exactly 5/r^3 and 16/(3 r^5);
 (ii) the same A, B are obtained from Wilson's *mobility* scalars
 x^g, y^g via A = 4(x11g - x12g)/r, B = 8(y11g - y12g)/r (agreement to 1e-7);
 (iii) near contact the table gives (1-A)/xi -> 4.0770 (BG: 4.077).

 Piece 1, r >= R_JOIN = 4.5: power series in 1/r, coefficients obtained
   (rational arithmetic on power series) from the Jeffrey-Onishi/Jeffrey-1992
   far-field coefficients f_k(lambda=1) as tabulated in Kengo Ichiki's
   libstokes, github.com/kichiki/libstokes @7604f51, src/{XA,YA,YB,YC,XG,YG,
   YH}.c with the normalisations of src/twobody.c (twobody_*_far); see
   Leading terms:
     A = 5/r^3 - 8/r^5 + 25/r^6 - 35/r^8 + 125/r^9 - 102/r^10 + (25/2)/r^11
         + (935/2)/r^12 - (1245/2)/r^13 + 970/r^14 + ...   (to r^-24 below)
     B = (16/3)/r^5 + (10/3)/r^8 - 12/r^10 - (25/3)/r^11 - 12/r^12
         + (115/3)/r^13 + (743/6)/r^14 + ...                (to r^-24 below)
   Truncation error at the join r = 4.5: |dA| ~ 2e-11, |dB|/B ~ 4e-10
   (vs. the full 150-term libstokes sum, which in turn matches the Wilson
   values of piece 2 at r = 4.5 to ~1e-9).
   The terms 5/r^3 - 8/r^5 of A and 16/(3r^5) of B (and the absence of
   r^-6, r^-7 terms in B at first reflection) were re-derived by hand (Faxen).  NOTE: the higher B coefficients
   could NOT be confirmed from the text of Batchelor & Green (1972) (not in the
   searchable corpora); the values above are the ones consistent with two
   independent numerical sources (libstokes series and Wilson's Lamb-method
   code), e.g. B(4.5) = 2.90613e-3.
 Piece 2, 2.00001 <= r <= 4.5: natural cubic spline in u = ln(r - 2) of
   g_A = (1-A)/(r-2) and ln B, through nodes computed with the formulas above
   from the lambda = 1 rows of Adam Townsend's table
   github.com/Pecnut/stokesian-dynamics @6b9117d,
   find_resistance_scalars/scalars_general_resistance.txt  (columns XA YA YB
   YC XG YG YH; rows gamma=0 -> "11", gamma=1 -> "12").  In that table
   r <= 2.02 comes from the corrected near-field (lubrication) forms of
   Jeffrey & Onishi 1984 / Jeffrey 1992 (Townsend 2023, Phys. Fluids 35,
   127126), r >= 2.025 from Wilson's Lamb's-method two-sphere code
   (Wilson 2013, J. Comput. Phys. 245, 302).  The r = 2.02 row is EXCLUDED
   from the spline: the repository README states the lambda=1 near-field forms
   are valid for s' < 2.01, and the row is inconsistent with its neighbours by
   ~1 % in B.  Remaining interpolation/near-field uncertainty: ~0.5-1 % in B and
   ~0.1-0.3 % in (1-A) for 2.002 < r < 2.05, <1e-6 for r > 2.2 (checked against
   the libstokes far-field series summed to k = 150).
 Piece 3, r < 2.00001 (beyond the table; NOT reached by any case printed
   here): 1-A = c xi with c = g_A at the first node (4.0770), and
   B = B0 - b1/(ln(1/xi) + b2) fitted through the three closest nodes
   (gives B0 ~ 0.40, consistent with the contact value 0.406 quoted for BG).
   This piece is a fit, not a literature formula.
------------------------------------------------------------------------------
"""
import math
import bisect

R_JOIN = 4.5

# Townsend table, lambda = 1 :  (s', XA11, XA12, YA11, YA12, YB11, YB12,
#   YC11, YC12, XG11, XG12, YG11, YG12, YH11, YH12)   [values copied verbatim]
TOWNSEND_LAMBDA1 = [
    (2.00001, 2.50035858e+04, -2.50029406e+04, 2.91713802e+00, -2.19247292e+00, -2.63932618e+00, 2.87662308e+00, 3.00544095e+00, 5.48189445e-01, 3.75034164e+04, -3.75036901e+04, 1.29796550e+00, -1.33662228e+00, 2.13819451e-01, 1.12200876e+00),
    (2.00002, 1.25034299e+04, -1.25027846e+04, 2.80161349e+00, -2.07694839e+00, -2.46605205e+00, 2.70334894e+00, 2.86683056e+00, 5.13538364e-01, 1.87531825e+04, -1.87534562e+04, 1.21132843e+00, -1.24998521e+00, 1.96497708e-01, 1.05269977e+00),
    (2.00005, 5.00322372e+03, -5.00257845e+03, 2.64889837e+00, -1.92423327e+00, -2.23701421e+00, 2.47431110e+00, 2.68362482e+00, 4.67741112e-01, 7.50287332e+03, -7.50314702e+03, 1.09680951e+00, -1.13546630e+00, 1.73609536e-01, 9.61086443e-01),
    (2.00010, 2.50306777e+03, -2.50242250e+03, 2.53337384e+00, -1.80870874e+00, -2.06378065e+00, 2.30107754e+00, 2.54507545e+00, 4.33110156e-01, 3.75263947e+03, -3.75291317e+03, 1.01019273e+00, -1.04884951e+00, 1.56310028e-01, 8.91795786e-01),
    (2.00020, 1.25291183e+03, -1.25226657e+03, 2.41784931e+00, -1.69318421e+00, -1.89059165e+00, 2.12788855e+00, 2.40659310e+00, 3.98501306e-01, 1.87740570e+03, -1.87767940e+03, 9.23598231e-01, -9.62255017e-01, 1.39034943e-01, 8.22525274e-01),
    (2.00050, 5.02705724e+02, -5.02060458e+02, 2.26513419e+00, -1.54046909e+00, -1.66178110e+00, 1.89907799e+00, 2.22372919e+00, 3.52816785e-01, 7.52096888e+02, -7.52370591e+02, 8.09192952e-01, -8.47849739e-01, 1.16271320e-01, 7.31014682e-01),
    (2.00100, 2.52549849e+02, -2.51904583e+02, 2.14960966e+00, -1.42494456e+00, -1.48888271e+00, 1.72617961e+00, 2.08568393e+00, 3.18352078e-01, 3.76863600e+02, -3.77137303e+02, 7.22743761e-01, -7.61400548e-01, 9.91554911e-02, 6.61875526e-01),
    (2.00200, 1.27394039e+02, -1.26748773e+02, 2.03408513e+00, -1.30942003e+00, -1.31628610e+00, 1.55358299e+00, 1.94809253e+00, 2.84037050e-01, 1.89130816e+02, -1.89404519e+02, 6.36445455e-01, -6.75102241e-01, 8.22050316e-02, 5.92872771e-01),
    (2.00500, 5.21882502e+01, -5.15429845e+01, 1.88137001e+00, -1.15670491e+00, -1.08897122e+00, 1.32626811e+00, 1.76747811e+00, 2.39094380e-01, 7.63245063e+01, -7.65982089e+01, 5.22788012e-01, -5.61444798e-01, 6.02610357e-02, 5.02038222e-01),
    (2.01000, 2.70328160e+01, -2.63875503e+01, 1.76584548e+00, -1.04118038e+00, -9.18129435e-01, 1.15542633e+00, 1.63252597e+00, 2.05649749e-01, 3.85946558e+01, -3.88683584e+01, 4.37367121e-01, -4.76023908e-01, 4.42722241e-02, 4.33828650e-01),
    (2.02000, 1.43777201e+01, -1.37324544e+01, 1.65032095e+00, -9.25655847e-01, -7.48866235e-01, 9.86163127e-01, 1.49994803e+00, 1.72988093e-01, 1.96174438e+01, -1.98911464e+01, 3.52735521e-01, -3.91392308e-01, 2.91484745e-02, 3.66332597e-01),
    (2.02500, 1.18308730e+01, -1.11842820e+01, 1.61590039e+00, -8.89093248e-01, -7.02024331e-01, 9.35578689e-01, 1.46432992e+00, 1.62461604e-01, 1.58037971e+01, -1.60759364e+01, 3.29727734e-01, -3.67331831e-01, 2.54866110e-02, 3.45628585e-01),
    (2.05000, 6.67965088e+00, -6.03161686e+00, 1.50311680e+00, -7.74182446e-01, -5.43189570e-01, 7.73049775e-01, 1.34305909e+00, 1.31261868e-01, 8.09106562e+00, -8.36148633e+00, 2.50597799e-01, -2.87183659e-01, 1.31997134e-02, 2.80553957e-01),
    (2.10000, 4.03209762e+00, -3.38119748e+00, 1.39300628e+00, -6.59875260e-01, -3.94506440e-01, 6.17143953e-01, 1.23302792e+00, 1.01739905e-01, 4.14245353e+00, -4.40942406e+00, 1.76820707e-01, -2.11438886e-01, 3.76787258e-03, 2.18019484e-01),
    (2.20000, 2.64104859e+00, -1.98449420e+00, 1.28803765e+00, -5.46750955e-01, -2.61871657e-01, 4.70734368e-01, 1.13980694e+00, 7.42610043e-02, 2.09086839e+00, -2.35089415e+00, 1.11592065e-01, -1.42550244e-01, -1.90434870e-03, 1.59204689e-01),
    (2.30000, 2.14662002e+00, -1.48451322e+00, 1.23065676e+00, -4.81539733e-01, -1.94738541e-01, 3.90725969e-01, 1.09559483e+00, 5.92549955e-02, 1.37682927e+00, -1.62986529e+00, 7.90642482e-02, -1.06722801e-01, -3.29176729e-03, 1.27153010e-01),
    (2.40000, 1.88607530e+00, -1.21851553e+00, 1.19255411e+00, -4.35937314e-01, -1.52907621e-01, 3.36909972e-01, 1.06962281e+00, 4.91618019e-02, 1.00915890e+00, -1.25517719e+00, 5.91420364e-02, -8.38457500e-02, -3.47797147e-03, 1.05765006e-01),
    (2.50000, 1.72266708e+00, -1.04975157e+00, 1.16486469e+00, -4.01078913e-01, -1.24149048e-01, 2.97030705e-01, 1.05273781e+00, 4.17153952e-02, 7.84088068e-01, -1.02307749e+00, 4.57144728e-02, -6.77859677e-02, -3.25291049e-03, 9.01032647e-02),
    (2.60000, 1.60952987e+00, -9.31353642e-01, 1.14364637e+00, -3.73018214e-01, -1.03175348e-01, 2.65761568e-01, 1.04106986e+00, 3.59332835e-02, 6.32091959e-01, -8.64058365e-01, 3.61406698e-02, -5.58761310e-02, -2.89493700e-03, 7.80030942e-02),
    (2.70000, 1.52605113e+00, -8.42707119e-01, 1.12680241e+00, -3.49650591e-01, -8.72535064e-02, 2.40321441e-01, 1.03266449e+00, 3.12972618e-02, 5.22746798e-01, -7.47714592e-01, 2.90555444e-02, -4.67228297e-02, -2.51479789e-03, 6.83230386e-02),
    (2.80000, 1.46166814e+00, -7.73247516e-01, 1.11308670e+00, -3.29719273e-01, -7.48062914e-02, 2.19080186e-01, 1.02642067e+00, 2.74977258e-02, 4.40547921e-01, -6.58562643e-01, 2.36706562e-02, -3.95092954e-02, -2.15725699e-03, 6.03874449e-02),
    (2.90000, 1.41037325e+00, -7.16965953e-01, 1.10170027e+00, -3.12412721e-01, -6.48523268e-02, 2.01001997e-01, 1.02167037e+00, 2.43332577e-02, 3.76727834e-01, -5.87858461e-01, 1.94947353e-02, -3.37172307e-02, -1.83859293e-03, 5.37631735e-02),
    (3.00000, 1.36847960e+00, -6.70175041e-01, 1.09210175e+00, -2.97175858e-01, -5.67464848e-02, 1.85388140e-01, 1.01798571e+00, 2.16646652e-02, 3.25938286e-01, -5.30278172e-01, 1.62044262e-02, -2.89982523e-02, -1.56235633e-03, 4.81558479e-02),
    (3.10000, 1.33358941e+00, -6.30477064e-01, 1.08390862e+00, -2.83611904e-01, -5.00464527e-02, 1.71744942e-01, 1.01508117e+00, 1.93914538e-02, 2.84722714e-01, -4.82388885e-01, 1.35779348e-02, -2.51079126e-02, -1.32653303e-03, 4.33562763e-02),
    (3.20000, 1.30407028e+00, -5.96240126e-01, 1.07684156e+00, -2.71427176e-01, -4.44386486e-02, 1.59710579e-01, 1.01275987e+00, 1.74386555e-02, 2.50743396e-01, -4.41874449e-01, 1.14582174e-02, -2.18689352e-02, -1.12691097e-03, 3.92105143e-02),
    (3.30000, 1.27876898e+00, -5.66311738e-01, 1.07069114e+00, -2.60398095e-01, -3.96945885e-02, 1.49011846e-01, 1.01088240e+00, 1.57489267e-02, 2.22360425e-01, -4.07113511e-01, 9.73124366e-03, -1.91494007e-02, -9.58687197e-04, 3.56020616e-02),
    (3.40000, 1.25684552e+00, -5.39852729e-01, 1.06529688e+00, -2.50350460e-01, -3.56439412e-02, 1.39437318e-01, 1.00934787e+00, 1.42775396e-02, 1.98388408e-01, -3.76935783e-01, 8.31251289e-03, -1.68491054e-02, -8.17201154e-04, 3.24407198e-02),
    (3.50000, 1.23767225e+00, -5.16236184e-01, 1.06053357e+00, -2.41145882e-01, -3.21572349e-02, 1.30820004e-01, 1.00808186e+00, 1.29890443e-02, 1.77948876e-01, -3.50474373e-01, 7.13834401e-03, -1.48906390e-02, -6.98242933e-04, 2.96553363e-02),
    (3.60000, 1.22076987e+00, -4.94983353e-01, 1.05630194e+00, -2.32672599e-01, -2.91343919e-02, 1.23025712e-01, 1.00702856e+00, 1.18549736e-02, 1.60376956e-01, -3.27072641e-01, 6.16006045e-03, -1.32133570e-02, -5.98152689e-04, 2.71888958e-02),
    (3.70000, 1.20576550e+00, -4.75721651e-01, 1.05252230e+00, -2.24839069e-01, -2.64969157e-02, 1.15945012e-01, 1.00614554e+00, 1.08522122e-02, 1.45160343e-01, -3.06223487e-01, 5.33999946e-03, -1.17691813e-02, -5.13813725e-04, 2.49951042e-02),
    (3.80000, 1.19236430e+00, -4.58156268e-01, 1.04912987e+00, -2.17569385e-01, -2.41824384e-02, 1.09487531e-01, 1.00540013e+00, 9.96180920e-03, 1.31898114e-01, -2.87528571e-01, 4.64870916e-03, -1.05196023e-02, -4.42608388e-04, 2.30359469e-02),
    (3.90000, 1.18032984e+00, -4.42050508e-01, 1.04607146e+00, -2.10799926e-01, -2.21408382e-02, 1.03577819e-01, 1.00476687e+00, 9.16809712e-03, 1.20272260e-01, -2.70670251e-01, 4.06294133e-03, -9.43349545e-03, -3.82354249e-04, 2.12799025e-02),
    (4.00000, 1.16947014e+00, -4.27211856e-01, 1.04330302e+00, -2.04476858e-01, -2.03314200e-02, 9.81522764e-02, 1.00422573e+00, 8.45802368e-03, 1.10027539e-01, -2.55391830e-01, 3.56419012e-03, -8.48550280e-03, -3.31239739e-04, 1.97006133e-02),
    (4.10000, 1.15962761e+00, -4.13481905e-01, 1.04078771e+00, -1.98554242e-01, -1.87208381e-02, 9.31568440e-02, 1.00376080e+00, 7.82064515e-03, 1.00956915e-01, -2.41483354e-01, 3.13761198e-03, -7.65481539e-03, -2.87764386e-04, 1.82758719e-02),
    (4.20000, 1.15067158e+00, -4.00728946e-01, 1.03849457e+00, -1.92992580e-01, -1.72815402e-02, 8.85452281e-02, 1.00335934e+00, 7.24672710e-03, 9.28908813e-02, -2.28771256e-01, 2.77121825e-03, -6.92424530e-03, -2.50686329e-04, 1.69868451e-02),
    (4.30000, 1.14249274e+00, -3.88842435e-01, 1.03639732e+00, -1.87757675e-01, -1.59905882e-02, 8.42775219e-02, 1.00301105e+00, 6.72843448e-03, 8.56894791e-02, -2.17110650e-01, 2.45526403e-03, -6.27951048e-03, -2.18977424e-04, 1.58174663e-02),
    (4.40000, 1.13499894e+00, -3.77728794e-01, 1.03447359e+00, -1.82819740e-01, -1.48287534e-02, 8.03191184e-02, 1.00270758e+00, 6.25908519e-03, 7.92362656e-02, -2.06379528e-01, 2.18178135e-03, -5.70867786e-03, -1.91785596e-04, 1.47539548e-02),
    (4.50000, 1.12811192e+00, -3.67308186e-01, 1.03270416e+00, -1.78152677e-01, -1.37798136e-02, 7.66398449e-02, 1.00244206e+00, 5.83295327e-03, 7.34336915e-02, -1.96474324e-01, 1.94421923e-03, -5.20172599e-03, -1.68403608e-04, 1.37844337e-02),
]
EXCLUDED_NODES = (2.02,)   # see docstring

# far-field series in 1/r (r >= R_JOIN), derived from the libstokes JO/J92
# coefficients f_k(lambda=1); truncation error at r=4.5: |dA|~2e-11, dB/B~4e-10
A_SERIES = {
    3: 5.0, 5: -8.0, 6: 25.0, 8: -35.0, 9: 125.0, 10: -102.0, 11: 25/2,
    12: 935/2, 13: -1245/2, 14: 970.0, 15: 2073/4, 16: -3123/4, 17: 6345/2,
    18: 9147/4, 19: -2855/4, 20: 11701.0, 21: 192373/8, 22: -67305/2,
    23: 331457/2, 24: -822325/8}
B_SERIES = {
    5: 16/3, 8: 10/3, 10: -12.0, 11: -25/3, 12: -12.0, 13: 115/3, 14: 743/6,
    15: 896/3, 16: 3049/6, 17: 4493/4, 18: 7813/8, 19: 2855.35,
    20: 523.708333333, 21: 5410.170833333, 22: -3095.125, 23: 8529.076041667,
    24: -12942.214583333}


def AB_from_resistance(row):
    """A, B from one row of resistance scalars (formulas in the docstring)."""
    (r, XA11, XA12, YA11, YA12, YB11, YB12, YC11, YC12,
     XG11, XG12, YG11, YG12, YH11, YH12) = row
    A = (4.0/3.0)*(XG11 - XG12)/(r*(XA11 - XA12))
    YAm, YBm, YGm = YA11 - YA12, YB11 - YB12, YG11 - YG12
    YCp, YHp = YC11 + YC12, YH11 + YH12
    B = 8.0*(YGm + YBm*YHp/YCp)/(r*(3.0*YAm - YBm**2/YCp))
    return A, B


class Spline:
    """Natural cubic spline (plain floats)."""
    def __init__(self, xs, ys):
        n = len(xs)
        h = [xs[i+1]-xs[i] for i in range(n-1)]
        al = [0.0]*n
        for i in range(1, n-1):
            al[i] = 3/h[i]*(ys[i+1]-ys[i]) - 3/h[i-1]*(ys[i]-ys[i-1])
        l, mu, z = [1.0]+[0.0]*(n-1), [0.0]*n, [0.0]*n
        for i in range(1, n-1):
            l[i] = 2*(xs[i+1]-xs[i-1]) - h[i-1]*mu[i-1]
            mu[i] = h[i]/l[i]
            z[i] = (al[i]-h[i-1]*z[i-1])/l[i]
        c, b, d = [0.0]*n, [0.0]*n, [0.0]*n
        for j in range(n-2, -1, -1):
            c[j] = z[j]-mu[j]*c[j+1]
            b[j] = (ys[j+1]-ys[j])/h[j] - h[j]*(c[j+1]+2*c[j])/3
            d[j] = (c[j+1]-c[j])/(3*h[j])
        self.xs, self.ys, self.b, self.c, self.d = xs, ys, b, c, d

    def __call__(self, x):
        i = min(max(bisect.bisect_right(self.xs, x)-1, 0), len(self.xs)-2)
        t = x-self.xs[i]
        return self.ys[i]+t*(self.b[i]+t*(self.c[i]+t*self.d[i]))


class Mobility:
    """A(r), B(r) for equal spheres; optional perturbations for sensitivity."""
    def __init__(self, exclude=EXCLUDED_NODES, nearA=1.0, Bfac=1.0,
                 Bwin=None, farfac=1.0):
        self.nearA, self.Bfac, self.Bwin, self.farfac = nearA, Bfac, Bwin, farfac
        us, gA, lB = [], [], []
        for row in TOWNSEND_LAMBDA1:
            r = row[0]
            if any(abs(r-e) < 1e-9 for e in exclude):
                continue
            A, B = AB_from_resistance(row)
            us.append(math.log(r-2.0)); gA.append((1.0-A)/(r-2.0)); lB.append(math.log(B))
        self.u0 = us[0]
        self.sA, self.sB = Spline(us, gA), Spline(us, lB)
        # piece 3: fit B = B0 - b1/(L + b2), L = ln(1/xi), through first 3 nodes
        (L1, L2, L3) = (-us[0], -us[1], -us[2])
        (B1, B2, B3) = (math.exp(lB[0]), math.exp(lB[1]), math.exp(lB[2]))
        # solve for b2 by bisection on the ratio condition
        def ratio(b2):
            return (B1-B2)/(B2-B3) - (1/(L2+b2)-1/(L1+b2))/(1/(L3+b2)-1/(L2+b2))
        lo, hi = -min(L1, L2, L3)+1e-6, 1e3
        for _ in range(200):
            mid = 0.5*(lo+hi)
            if ratio(lo)*ratio(mid) <= 0: hi = mid
            else: lo = mid
        self.b2 = 0.5*(lo+hi)
        self.b1 = (B1-B2)/(1/(L2+self.b2)-1/(L1+self.b2))
        self.B0 = B1 + self.b1/(L1+self.b2)
        self.c0 = gA[0]

    # --- near-field-smooth quantities --------------------------------------
    def gA_B(self, r):
        """Return (gA = (1-A)/(r-2), B) -- gA is what the ODE needs."""
        if r >= R_JOIN:
            A = sum(c/r**k for k, c in A_SERIES.items())
            Bv = sum(c/r**k for k, c in B_SERIES.items())
            if self.farfac != 1.0:   # scale everything beyond the leading terms
                A = 5/r**3 + self.farfac*(A-5/r**3)
                Bv = 16/(3*r**5) + self.farfac*(Bv-16/(3*r**5))
            g = (1.0-A)/(r-2.0)
        else:
            u = math.log(r-2.0)
            if u >= self.u0:
                g = self.sA(u); Bv = math.exp(self.sB(u))
            else:
                L = -u
                g = self.c0; Bv = self.B0 - self.b1/(L+self.b2)
        if self.nearA != 1.0:         # scale (1-A) near contact, smooth blend
            w = blend(r, 2.05, 2.5)
            g *= 1.0 + (self.nearA-1.0)*w
        if self.Bfac != 1.0:
            if self.Bwin is None or self.Bwin[0] <= r <= self.Bwin[1]:
                Bv *= self.Bfac
        return g, Bv

    def AB(self, r):
        g, Bv = self.gA_B(r)
        return 1.0-g*(r-2.0), Bv


def blend(r, r1, r2):
    """1 for r <= r1, 0 for r >= r2, cosine in between."""
    if r <= r1: return 1.0
    if r >= r2: return 0.0
    return 0.5*(1+math.cos(math.pi*(r-r1)/(r2-r1)))


# ============================================================================
# First integral (exact Batchelor & Green shear-plane solution)
# ============================================================================
class FirstIntegral:
    """Tabulates I(u), q(u), J(u) on a uniform grid in u = ln(r-2), RK4 from
    r = 2 + exp(U_MAX) inwards; q s - J = y_inf^2 on every trajectory."""
    U_MAX, U_MIN = math.log(1.0e4), math.log(2.0e-6)

    def __init__(self, mob, N=4000):
        self.mob, self.N = mob, N
        self.h = (self.U_MIN-self.U_MAX)/N          # negative
        R0 = 2.0+math.exp(self.U_MAX)
        I0 = 10.0/(3*R0**3)                          # tail: 2(A-B)/(r(1-A)) ~ 10/r^4
        J0 = 16.0/(9*R0**3)                          # tail: q B/(r(1-A)) ~ (16/3)/r^4
        self.us, self.I, self.J = [self.U_MAX], [I0], [J0]
        y = (I0, J0); u = self.U_MAX
        for _ in range(N):
            y = self._step(u, y, self.h); u += self.h
            self.us.append(u); self.I.append(y[0]); self.J.append(y[1])

    def _rhs(self, u, y):
        xi = math.exp(u); r = 2.0+xi
        g, B = self.mob.gA_B(r)
        A = 1.0-g*xi
        # dI/du = -2(A-B)/(r(1-A)) * dr/du ; dr/du = xi ; (1-A) = g xi
        dI = -2.0*(A-B)/(r*g)
        q = r*r*math.exp(-y[0])
        dJ = -q*B/(r*g)
        return (dI, dJ)

    def _step(self, u, y, h):
        k1 = self._rhs(u, y)
        k2 = self._rhs(u+h/2, (y[0]+h/2*k1[0], y[1]+h/2*k1[1]))
        k3 = self._rhs(u+h/2, (y[0]+h/2*k2[0], y[1]+h/2*k2[1]))
        k4 = self._rhs(u+h, (y[0]+h*k3[0], y[1]+h*k3[1]))
        return (y[0]+h/6*(k1[0]+2*k2[0]+2*k3[0]+k4[0]),
                y[1]+h/6*(k1[1]+2*k2[1]+2*k3[1]+k4[1]))

    def _at(self, u):
        """(r, q, J) at arbitrary u (one partial RK4 step from nearest node)."""
        i = int((u-self.U_MAX)/self.h)
        i = min(max(i, 0), self.N)
        y = (self.I[i], self.J[i])
        du = u-self.us[i]
        if du != 0.0:
            y = self._step(self.us[i], y, du)
        r = 2.0+math.exp(u)
        return r, r*r*math.exp(-y[0]), y[1]

    def invariant(self, r, s):
        """y_inf^2 of the trajectory through (r, sin^2 th = s)."""
        _, q, J = self._at(math.log(r-2.0))
        return q*s-J

    def rmin(self, yinf2):
        """closest approach r_min: q - J = yinf2."""
        F = [r*r*math.exp(-I)-J for r, I, J in
             zip((2+math.exp(u) for u in self.us), self.I, self.J)]
        for i in range(1, len(F)):
            if (F[i-1]-yinf2)*(F[i]-yinf2) <= 0.0:
                lo, hi = self.us[i-1], self.us[i]
                for _ in range(100):
                    mid = 0.5*(lo+hi)
                    _, q, J = self._at(mid)
                    if (q-J-yinf2)*(F[i-1]-yinf2) > 0: lo = mid
                    else: hi = mid
                return 2.0+math.exp(0.5*(lo+hi))
        return float('nan')


# ============================================================================
# Time integration of the ODE (RK4 in rho = ln(r-2), theta)
# ============================================================================
def rhs_t(mob, y):
    rho, th = y
    xi = math.exp(rho); r = 2.0+xi
    g, B = mob.gA_B(r)
    # dr/dt = r (1-A) sin cos  ->  drho/dt = r g sin cos   (no stiffness)
    return (r*g*math.sin(th)*math.cos(th),
            -(math.sin(th)**2 + 0.5*B*math.cos(2*th)))


def rk4_t(mob, y, dt):
    k1 = rhs_t(mob, y)
    k2 = rhs_t(mob, (y[0]+dt/2*k1[0], y[1]+dt/2*k1[1]))
    k3 = rhs_t(mob, (y[0]+dt/2*k2[0], y[1]+dt/2*k2[1]))
    k4 = rhs_t(mob, (y[0]+dt*k3[0], y[1]+dt*k3[1]))
    return (y[0]+dt/6*(k1[0]+2*k2[0]+2*k3[0]+k4[0]),
            y[1]+dt/6*(k1[1]+2*k2[1]+2*k3[1]+k4[1]))


def integrate(mob, x0, y0, dt, t_end):
    """RK4 from relative position (x0, y0) [units of a] up to t = t_end.
    Records the closest approach (cos theta = 0, where dr/dt changes sign).
    Returns dict(t_min, r_min, x, y, r) with (x, y, r) at t_end."""
    r0 = math.hypot(x0, y0)
    y = (math.log(r0-2.0), math.atan2(y0, x0))
    t, out = 0.0, {}
    nsteps = int(t_end/dt + 1e-9)
    for n in range(nsteps+1):
        h = dt if n < nsteps else t_end - t
        if h <= 1e-14:
            break
        ynew = rk4_t(mob, y, h)
        c0, c1 = math.cos(y[1]), math.cos(ynew[1])
        if 't_min' not in out and c0*c1 <= 0.0 and c0 != 0.0:
            lo, hi = 0.0, h          # bisection for cos(theta) = 0 inside step
            for _ in range(60):
                mid = 0.5*(lo+hi)
                if math.cos(rk4_t(mob, y, mid)[1])*c0 > 0: lo = mid
                else: hi = mid
            ym = rk4_t(mob, y, 0.5*(lo+hi))
            out['t_min'], out['r_min'] = t+0.5*(lo+hi), 2.0+math.exp(ym[0])
        y, t = ynew, t+h
    out['x'], out['y'] = pos(y)
    out['r'] = 2.0+math.exp(y[0])
    return out


def pos(y):
    r = 2.0+math.exp(y[0]); return r*math.cos(y[1]), r*math.sin(y[1])


# ============================================================================
# Driver
# ============================================================================
A_RADIUS = 0.05                      # sphere radius of the fidus test case
CENTROID = (0.5, 0.5, 0.5)           # centroid of the pair (moves with u(0.5)=0)


def fmt(x, n=6):
    return ("%." + str(n) + "f") % x


def main():
    mob = Mobility()
    P = print
    P("=" * 78)
    P("Batchelor & Green (1972) pair trajectory in simple shear -- reference")
    P("=" * 78)

    # ------------------------------------------------------------------ 1
    P("\n[1] Mobility functions A(r), B(r)   (r = centre distance / a)")
    P("   r            1-A            B              A*r^3      B*r^5")
    for r in (2.00001, 2.0001, 2.001, 2.005, 2.01, 2.025, 2.05, 2.1, 2.2,
              2.5, 3.0, 3.5, 4.0, 4.5, 6.0, 10.0, 100.0, 1000.0):
        A, B = mob.AB(r)
        P("   %-11.5f  %.8e  %.8e  %9.5f  %9.5f" % (r, 1-A, B, A*r**3, B*r**5))
    # checks
    A, B = mob.AB(1000.0)
    ok_far = abs(A*1e9-5) < 1e-4 and abs(B*1e15-16/3) < 1e-4
    P("   CHECK far field: A r^3 -> 5 (%.6f), B r^5 -> 16/3=%.6f (%.6f): %s"
      % (A*1e9, 16/3, B*1e15, "PASS" if ok_far else "FAIL"))
    rowj = [row for row in TOWNSEND_LAMBDA1 if abs(row[0]-4.5) < 1e-12][0]
    Aj, Bj = AB_from_resistance(rowj)
    As = sum(c/4.5**k for k, c in A_SERIES.items())
    Bs = sum(c/4.5**k for k, c in B_SERIES.items())
    P("   CHECK join r=4.5: table A=%.9f series A=%.9f | table B=%.9e series B=%.9e : %s"
      % (Aj, As, Bj, Bs, "PASS" if abs(Aj-As) < 1e-8 and abs(Bj/Bs-1) < 1e-7 else "FAIL"))
    P("   CHECK near contact: (1-A)/xi at xi=1e-5 = %.5f (BG 1972 as quoted: 4.077)"
      % mob.c0)
    P("   near-contact fit B = B0 - b1/(ln(1/xi)+b2): B0=%.4f b1=%.4f b2=%.4f "
      "(contact value quoted for BG: 0.406)" % (mob.B0, mob.b1, mob.b2))

    # ------------------------------------------------------------------ 2
    P("\n[2] Upstream offset y_inf (pair from x = -inf, shear plane): exact first integral")
    fi = FirstIntegral(mob, N=4000)
    fi2 = FirstIntegral(mob, N=8000)
    P("   y_inf/a   r_min/a (N=4000)  r_min/a (N=8000)   d_min=r_min/2a   gap (r_min-2)a")
    res = {}
    for yinf in (0.5, 1.0, 2.0):
        r1, r2 = fi.rmin(yinf**2), fi2.rmin(yinf**2)
        res[yinf] = r2
        P("   %-7.2f   %.9f       %.9f        %.7f        %.4e   conv %s"
          % (yinf, r1, r2, r2/2, r2-2, "PASS" if abs(r1-r2) < 1e-7 else "FAIL"))
    rc = fi2.rmin(0.0)
    P("   limiting open trajectory (y_inf -> 0+): r_c = %.7f  (gap %.2e a); "
      "r_min < r_c only on closed orbits" % (rc, rc-2))

    # ------------------------------------------------------------------ 3
    P("\n[3] Cross-check by RK4 time integration from x = -30a on the same trajectories")
    P("   (two step sizes; symmetry: position at t = 2 t_min must be the mirror image)")
    R0 = 30.0
    for yinf in (0.5, 1.0, 2.0):
        _, q, J = fi2._at(math.log(R0-2.0))
        s0 = (yinf**2 + J)/q
        th0 = math.pi - math.asin(math.sqrt(s0))
        x0, y0 = R0*math.cos(th0), R0*math.sin(th0)
        line = "   y_inf=%.1f start (%.4f, %.6f):" % (yinf, x0, y0)
        for dt in (0.02, 0.01):
            o = integrate(mob, x0, y0, dt, 3.0*R0/yinf + 50)
            o2 = integrate(mob, x0, y0, dt, 2*o['t_min'])
            sym = abs(o2['x']+x0) < 1e-5 and abs(o2['y']-y0) < 1e-6
            agree = abs(o['r_min']-res[yinf]) < 1e-7
            line += ("\n      dt=%.3f  t_min=%.6f r_min=%.9f | at 2t_min: x=%.6f "
                     "(mirror %.6f) y=%.8f (start %.8f)  symmetry %s, r_min vs first integral %s"
                     % (dt, o['t_min'], o['r_min'], o2['x'], -x0, o2['y'], y0,
                        "PASS" if sym else "FAIL", "PASS" if agree else "FAIL"))
            inv = fi2.invariant(math.hypot(o['x'], o['y']),
                                (o['y']/math.hypot(o['x'], o['y']))**2)
        line += "\n      first-integral invariant at end of run: y_inf^2 = %.8f (exact %.8f)" % (inv, yinf**2)
        P(line)

    # ------------------------------------------------------------------ 4
    P("\n[4] Finite start: sphere0 (0.3,0.525,0.5), sphere1 (0.7,0.475,0.5), a=0.05,"
      " u = (y-0.5) e_x")
    x0, y0 = (0.7-0.3)/A_RADIUS, (0.475-0.525)/A_RADIUS      # (8, -1) in units of a
    P("   relative position X1-X0 = (%.3f, %.3f, 0) a" % (x0, y0))
    yinf2 = fi2.invariant(math.hypot(x0, y0), (y0/math.hypot(x0, y0))**2)
    rfi = fi2.rmin(yinf2)
    P("   first integral: equivalent upstream offset |y_inf| = %.7f a;  r_min = %.9f a"
      % (math.sqrt(yinf2), rfi))
    T = 16.0
    summary = []
    for dt in (0.01, 0.005):
        o = integrate(mob, x0, y0, dt, T)
        o2 = integrate(mob, x0, y0, dt, 2*o['t_min'])
        P("   RK4 dt=%.3f: t_min=%.6f  r_min=%.9f  d_min=|X1-X0|min/2a=%.7f  gap=%.4e a"
          % (dt, o['t_min'], o['r_min'], o['r_min']/2, o['r_min']-2))
        P("        at t=16: (x1-x0)/2a=%.6f  (y1-y0)/2a=%.7f  |X1-X0|/2a=%.6f"
          % (o['x']/2, o['y']/2, o['r']/2))
        sym = abs(o2['x']+x0) < 1e-5 and abs(o2['y']-y0) < 1e-6
        P("        symmetry at t=2 t_min=%.4f: x=%.7f (expect %.3f) y=%.8f (expect %.3f): %s"
          % (2*o['t_min'], o2['x'], -x0, o2['y'], y0, "PASS" if sym else "FAIL"))
        summary.append(o)
    P("   step-size convergence: d r_min = %.1e, d t_min = %.1e, d y(16) = %.1e : %s"
      % (summary[0]['r_min']-summary[1]['r_min'], summary[0]['t_min']-summary[1]['t_min'],
         summary[0]['y']-summary[1]['y'],
         "PASS" if abs(summary[0]['r_min']-summary[1]['r_min']) < 1e-8 else "FAIL"))
    P("   RK4 r_min vs first-integral r_min: %.1e : %s"
      % (summary[1]['r_min']-rfi, "PASS" if abs(summary[1]['r_min']-rfi) < 1e-7 else "FAIL"))
    P("   time history (dt=0.005):   t    (x1-x0)/2a   (y1-y0)/2a   |X1-X0|/2a")
    for tt in (0.0, 2.0, 4.0, 6.0, 7.0, 7.5, 7.8937, 8.5, 10.0, 12.0, 14.0, 16.0):
        if tt == 0.0:
            xx, yy = x0, y0
        else:
            oo = integrate(mob, x0, y0, 0.005, tt); xx, yy = oo['x'], oo['y']
        P("                          %7.4f  %10.6f  %11.7f  %10.7f" % (tt, xx/2, yy/2, math.hypot(xx, yy)/2))
    # sphere positions (centroid fixed at (0.5,0.5,0.5) by symmetry)
    o = integrate(mob, x0, y0, 0.005, T)
    om = integrate(mob, x0, y0, 0.005, o['t_min'])
    for lab, oo in (("t_min", om), ("t=16 ", o)):
        dx, dy = oo['x']*A_RADIUS/2, oo['y']*A_RADIUS/2
        P("   sphere centres at %s: X0=(%.6f, %.6f, 0.5)  X1=(%.6f, %.6f, 0.5)"
          % (lab, CENTROID[0]-dx, CENTROID[1]-dy, CENTROID[0]+dx, CENTROID[1]+dy))

    # ------------------------------------------------------------------ 5
    P("\n[5] Sensitivity of r_min/a (first integral, N=4000) to the A, B data")
    cases = [("baseline", {}),
             ("(1-A) x1.10 for r<2.05 (blend to 2.5)", dict(nearA=1.10)),
             ("(1-A) x0.90 for r<2.05 (blend to 2.5)", dict(nearA=0.90)),
             ("(1-A) x1.01 for r<2.05 (blend to 2.5)", dict(nearA=1.01)),
             ("(1-A) x0.99 for r<2.05 (blend to 2.5)", dict(nearA=0.99)),
             ("B x1.10 everywhere", dict(Bfac=1.10)),
             ("B x0.90 everywhere", dict(Bfac=0.90)),
             ("B x1.01 on 2.001<r<2.05", dict(Bfac=1.01, Bwin=(2.001, 2.05))),
             ("B x0.99 on 2.001<r<2.05", dict(Bfac=0.99, Bwin=(2.001, 2.05))),
             ("far-field terms beyond 5/r^3,16/3r^5 x1.10", dict(farfac=1.10)),
             ("far-field terms beyond 5/r^3,16/3r^5 x0.90", dict(farfac=0.90)),
             ("include the r=2.02 near-field row", dict(exclude=()))]
    P("   %-44s %11s %11s %11s %11s" % ("perturbation", "y_inf=0.5", "y_inf=1", "y_inf=2", "(8,-1)start"))
    base = None
    for lab, kw in cases:
        m = Mobility(**kw)
        f = FirstIntegral(m, N=4000)
        vals = [f.rmin(y*y) for y in (0.5, 1.0, 2.0)]
        vals.append(f.rmin(f.invariant(math.hypot(x0, y0), (y0/math.hypot(x0, y0))**2)))
        if base is None:
            base = vals
            P("   %-44s %11.7f %11.7f %11.7f %11.7f" % (lab, *vals))
        else:
            P("   %-44s %+11.2e %+11.2e %+11.2e %+11.2e" % (lab, *[v-b for v, b in zip(vals, base)]))
    P("   (perturbed rows: change of r_min/a; d_min changes by half of this)")

    P("\n[6] SUMMARY (smooth spheres, unbounded Stokes shear, BG/JO mobility functions)")
    P("   case                      r_min/a       d_min=r_min/2a   gap/a        t_min*gdot")
    for yinf in (0.5, 1.0, 2.0):
        P("   y_inf = %.1f a (x=-inf)    %.7f     %.7f        %.3e    (infinite)"
          % (yinf, res[yinf], res[yinf]/2, res[yinf]-2))
    o = summary[1]
    P("   start (8a,-1a) [fidus]    %.7f     %.7f        %.3e    %.4f"
      % (o['r_min'], o['r_min']/2, o['r_min']-2, o['t_min']))
    P("   fidus case at t = 16: (y1-y0)/2a = %.6f, (x1-x0)/2a = %.5f; the mirror point"
      " (x,y)=(-8a,-1a) is reached at t = 2 t_min = %.4f" % (o['y']/2, o['x']/2, 2*o['t_min']))


if __name__ == "__main__":
    main()
