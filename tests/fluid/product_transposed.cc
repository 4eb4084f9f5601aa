// product_transposed(), the matrix product of the cut element's Nitsche
// terms and ghost-penalty faces, which WorkStream runs on several threads
// at once:
//  - against a plain triple loop, for the shapes its callers give it (the
//    Nitsche terms of a 2D and a 3D cut cell, the velocity and pressure
//    parts of a 3D ghost-penalty face): within 1e-13 of the largest entry;
//  - two threads computing the same products at the same time get, every
//    time, the matrix that one thread gets alone, to the bit. deal.II's
//    FullMatrix::mTmult fails this with Debian's serial OpenBLAS (its
//    buffers are shared without a lock): a few per cent of the products
//    come back wrong, which made the cut element's answers on two threads
//    differ from one thread's by 1e-2 now and then.

#include "../fidus_test.h"

#include <atomic>
#include <fidus/fluid/cut_element/product_transposed.h>
#include <thread>

using namespace FidusTest;

namespace
{
  dealii::FullMatrix<double>
  filled(const unsigned int m, const unsigned int n, const double seed)
  {
    dealii::FullMatrix<double> a(m, n);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < n; ++j)
        a(i, j) = std::sin(seed + 0.37 * i + 1.13 * j + 0.01 * i * j);
    return a;
  }

  /// The largest |product - left right^T| over the largest |product|.
  double
  error_against_loops(const dealii::FullMatrix<double> &left,
                      const dealii::FullMatrix<double> &right,
                      const dealii::FullMatrix<double> &product)
  {
    double error = 0., scale = 0.;
    for (unsigned int i = 0; i < left.m(); ++i)
      for (unsigned int j = 0; j < right.m(); ++j)
        {
          double sum = 0.;
          for (unsigned int k = 0; k < left.n(); ++k)
            sum += left(i, k) * right(j, k);
          error = std::max(error, std::abs(sum - product(i, j)));
          scale = std::max(scale, std::abs(sum));
        }
    return error / scale;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  struct Shape
  {
    std::string  name;
    unsigned int rows, columns, repeats;
  };
  // The Nitsche terms (cut_stokes_solve_assemble.cc): rows the Taylor-Hood
  // functions (2D: 9 x 2 + 4, 3D: 27 x 3 + 8) and one particle's rigid
  // modes (3 and 6), columns 2 dim per surface point (here 8 points in 2D,
  // 24 in 3D). A 3D face: rows the two cells' scalar Q2 functions (27 + 27
  // - 9 shared) with 2 columns per face point (9), and their pressures
  // (8 + 8 - 4) with one.
  const std::vector<Shape> shapes = {
    {"2D Nitsche terms", 25, 8 * 4, 20000},
    {"3D Nitsche terms", 95, 24 * 6, 1000},
    {"3D face, velocity part", 45, 9 * 2, 20000},
    {"3D face, pressure part", 12, 9, 50000}};
  for (const auto &shape : shapes)
    {
      const auto                 left  = filled(shape.rows, shape.columns, 0.1);
      const auto                 right = filled(shape.rows, shape.columns, 2.3);
      dealii::FullMatrix<double> alone;
      Fidus::product_transposed(left, right, alone);
      check_range(shape.name + ": error against the loops",
                  error_against_loops(left, right, alone),
                  0.,
                  1e-13);

      std::atomic<unsigned int> wrong{0};
      const auto                work = [&]() {
        dealii::FullMatrix<double> product;
        for (unsigned int r = 0; r < shape.repeats; ++r)
          {
            Fidus::product_transposed(left, right, product);
            for (unsigned int i = 0; i < product.m(); ++i)
              for (unsigned int j = 0; j < product.n(); ++j)
                if (product(i, j) != alone(i, j))
                  {
                    ++wrong;
                    i = product.m();
                    break;
                  }
          }
      };
      std::thread first(work), second(work);
      first.join();
      second.join();
      check_range(shape.name + ": products on two threads unlike one's",
                  wrong,
                  0,
                  0);
    }
  return exit_code();
}
