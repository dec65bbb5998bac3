// The exact torque-free gyrostat flow (src/integrate/gyrostat_flow.hpp) against references at 40 digits
// from an independent method: the Taylor series of Euler's gyrostat equation and of Ṙ = R[ω]× (order
// 40; docs/research/gyrostat_references.py prints the values below), and against the Taylor series in
// long double over random states.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>

#include "free_body_taylor.hpp"
#include "integrate/gyrostat_flow.hpp"
#include "integrate/gyrostat_series.hpp"

namespace tumble {
namespace {

struct Case {
  std::string name;
  Vec3 I, h, omega0;
  std::array<Vec3, 2> omega;               // at t = 10 s and 100 s
  std::array<std::array<double, 9>, 2> R;  // row-major, the same times
};

// R(0) from the unit quaternion (w, x, y, z) = (0.8, 0.2, −0.4, 0.4), exact in decimal.
const Quat kQ0(0.8, 0.2, -0.4, 0.4);

const Case kCases[] = {
    {"dual_spin",
     {1.0, 2.0, 3.0},
     {0, 1.5, 0},
     {0.01, 1.0, 0.02},
     {{{0.01250482939375591016999396, 1.000056373936187623090074, 0.01749406700418938473422956},
       {0.01382364465592886303539043, 1.000091101451047773623989, -0.01575314196477165070138563}}},
     {{{-0.5609299503197116030105918, -0.807880855743403474605785, 0.1807930135752816583760897,
        -0.7535576272943529971423952, 0.5886862343535834603826398, 0.2925737852732243530722898,
        -0.3427951183736881218291937, 0.0278754444969747088454004, -0.9389965209803842668582381},
       {0.085803020249806999506247, -0.8152300607017557053134857, -0.5727458335459306665103538,
        0.1028992619574615037411193, 0.5790427681717670547845276, -0.8087776051032737083477956,
        0.9909841490178442434043295, 0.01046043766717924067203675, 0.1335701899346936318335569}}}},
    {"off_axis",
     {1.0, 2.0, 3.0},
     {0.3, -0.4, 0.5},
     {0.7, 0.2, -0.4},
     {{{-0.9508381588690276302062065, 0.1617587048002840691661554, 0.1766116629606954772156842},
       {0.9181032008180383565477017, 0.2317693556455698557947043, -0.1822566361068438082228432}}},
     {{{-0.1834746728989573354606226, -0.848196121543727970618799, 0.4968907161567803515011312,
        -0.16705145594367488145298, 0.5250219147214269099152407, 0.8345332828170157405564983,
        -0.9687264089884816703611782, 0.07010940350925956179381986, -0.238020621097956053247803},
       {0.5293521077768075623449157, 0.1985712246013209368994378, -0.8248368412920114381228191,
        0.767823741855322057006621, 0.3014179211437792826337639, 0.5653263997520849982738563,
        0.3608781614832669059302529, -0.9325860311915969336229817, 0.007088511180983310175825788}}}},
    {"near_separatrix",
     {1.0, 2.0, 3.0},
     {0.001, 0.002, -0.0015},
     {0.3, 0.5, 0.1733},
     {{{0.04626556605232801577138449, 0.5820371461899044038878482, -0.0118839991596736545662436},
       {0.08488153573276359174110801, 0.5778044851297646006979725, -0.04154414848288045166462208}}},
     {{{0.4491862355098806714684801, -0.8361378527556063703687831, -0.314809810866348218676513,
        -0.05254852025022596192474478, 0.3270227375652856039934066, -0.9435543344899741023494028,
        0.8918914613606151171490614, 0.4403744092298623343620418, 0.102956305525577845199834},
       {-0.5589918613234606540827537, -0.7971885793936834188553495, -0.228075574883444810450427,
        -0.8061590087483547688111327, 0.4581567161750619756395879, 0.3744330060739220724296119,
        -0.1939993597618378539829241, 0.3931701823739493760200788, -0.8987666305020633080810143}}}},
    {"unsorted_axis_1",
     {2.5, 1.2, 1.9},
     {2.0, 0, 0},
     {0.3, -0.8, 0.5},
     {{{0.2575547852863167812555588, 0.3040393810625386287771928, -0.7918120115665507556522014},
       {0.3053107390717869376269698, -0.8419997185037354124153652, 0.4496824320188604955996528}}},
     {{{-0.08583242371719274768406995, 0.3601581554365088300781869, -0.928934280835519511805056,
        0.1218050189060370260776743, 0.9291743228074849404924009, 0.3489965833708859301853387,
        0.9888358470485039260205748, -0.08319363501989389680004855, -0.1236223551144550606044064},
       {0.1971603418741193168676378, -0.9509539138441012177511417, -0.2383578262542812152203091,
        0.4236700279675809018521963, 0.3019016213580641514886524, -0.8540252446054046708199098,
        0.884099263088726711499589, 0.0673948422800868469354121, 0.462413698153517732522632}}}},
    {"one_oval",
     {1.0, 2.0, 3.0},
     {0.01, 0.02, 0.03},
     {0.1, 0.2, 1.0},
     {{{0.07733398258349710002421072, -0.1712396274616128185302219, 1.004220001644956860913765},
       {-0.1992426664683120592407793, -0.001477127591945118284068003, 1.008348153507631705923584}}},
     {{{0.1823400922634016449568285, 0.8522522844730057653014598, -0.4903245194398471357272536,
        -0.8416119945789633145023674, -0.1225553007604322982813821, -0.525993772621253575096595,
        -0.5083712632852030121763081, 0.5085727498264755028952052, 0.6949190001717782656726881},
       {-0.3410846649433112403331426, -0.731715215875286292668352, -0.5901305738538652318300525,
        0.8767084218262407661189395, -0.02109991203766368663434171, -0.4805591917869692964518653,
        0.3391807695602027960801413, -0.6812838149909228789124107, 0.648697748563969177209741}}}},
    {"two_ovals",
     {1.0, 2.0, 3.0},
     {0.01, 0.02, 0.03},
     {0.5, 0.3, 0.8},
     {{{-0.3684094455093432337277184, 0.4466152744525024115013456, 0.7778911821308792271372089},
       {0.5696996464948657056905602, -0.05974637490693589912395417, 0.8202241673580429946728228}}},
     {{{-0.6530259481191555176037991, 0.07495773150281524006984267, -0.7536169116806163248164727,
        -0.08533997934813690528095625, -0.9960351615085888357518031, -0.02512060834094030149657854,
        -0.7525119261566141935026076, 0.04790924260005800458118038, 0.6568336969625958635308883},
       {-0.1907994473892911630802891, -0.7912710344374346542423104, -0.580935212339769618687494,
        0.8036911389864378110429769, 0.2138808288387411871203182, -0.555279699043585958935663,
        0.5636276465811656889657868, -0.5728395422066856564564472, 0.595129174964403326922924}}}},
    {"free_body",
     {3.0, 1.0, 2.0},
     {0, 0, 0},
     {0.4, 0.3, -0.6},
     {{{0.5175402717397936016137238, -0.6430737116517034324830006, -0.1909350711171255435964457},
       {0.4143243305074340426037298, 0.3535448381058622090349287, -0.5700930164882742017867743}}},
     {{{0.1323443177234444134866586, -0.9763277206174005018998907, 0.1710823296554823858854554,
        0.8803594141307594890643693, 0.03646849268420648817381724, -0.4729031095189456327189571,
        0.4554693003020751414554953, 0.2131999788822061041634082, 0.8643456979050482696282059},
       {-0.2966284176227384933418687, 0.3515075467042212107206209, -0.8879493377826293462792037,
        0.950484003226110385741971, 0.1989116443489606192360972, -0.2387767102413046999475933,
        0.09269164724988776177908719, -0.9148095989616486021430014, -0.3931051464655862621291162}}}},
};

double angle_between(const Quat& q, const std::array<double, 9>& R_ref) {
  const Mat3 R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R_ref.data());
  return Eigen::AngleAxisd(q.toRotationMatrix() * R.transpose()).angle();
}

TEST(GyrostatFlow, AgreesWithFortyDigitReferencesOverAHundredSeconds) {
  for (const Case& c : kCases) {
    const GyrostatFlow flow(c.I, c.h, kQ0, c.omega0);
    EXPECT_EQ(flow.regime(), GyrostatFlow::Regime::closed_form) << c.name;
    for (int k = 0; k < 2; ++k) {
      const double t = k == 0 ? 10.0 : 100.0;
      const GyrostatFlow::State s = flow.state(t);
      const double ew = (s.omega_b - c.omega[k]).norm(), eR = angle_between(s.q, c.R[k]);
      std::printf("%-16s t=%5.0f  T=%8.4f  |dw|=%.2e  angle=%.2e\n", c.name.c_str(), t, flow.period(), ew,
                  eR);
      EXPECT_LT(ew, 1e-12) << c.name << " at t = " << t;
      EXPECT_LT(eR, 1e-12) << c.name << " at t = " << t;
    }
  }
}

/// The flow at τ against the Taylor series of the same equations in long double (steps of ≤ 0.02 s at
/// order 30, |ω| ≤ 3 rad/s: truncation ~0.06³⁰, far below its rounding, ~1e-18 per step).
GyrostatFlow::State taylor_state(const Vec3& I, const Vec3& h, const Quat& q0, const Vec3& w0, double tau) {
  const FreeBodyTaylorT<long double> taylor(I, h, 30);
  FreeBodyStateT<long double> s = test::to_ld(q0, w0);
  const int steps = static_cast<int>(std::ceil(std::abs(tau) / 0.02));
  for (int i = 0; i < steps; ++i) s = taylor.step(s, static_cast<long double>(tau) / steps);
  return {test::quat_of(s), test::omega_of(s)};
}

TEST(GyrostatFlow, AgreesWithTheTaylorSeriesFromRandomStates) {
  std::mt19937_64 rng(26);
  std::uniform_real_distribution<double> moment(0.5, 3.0), unit(-1.0, 1.0);
  double worst[2] = {0, 0};
  // 100 bodies, a quarter with small rotors; forwards and backwards in time. Measured:
  // worst 1.0e-14 relative in ω, 2.1e-14 rad; the bound leaves room for states near a separatrix, where
  // the lattice's rounding is amplified (as 1/k′ of its Jacobi functions).
  for (int k = 0; k < 100; ++k) {
    const Vec3 I(moment(rng), moment(rng), moment(rng));
    const double scale = k % 4 == 0 ? 1e-3 : 1.0;  // small rotor momenta too: near the free body
    const Vec3 h = scale * Vec3(unit(rng), unit(rng), unit(rng)) * 2.0;
    const Vec3 w0(unit(rng), unit(rng), unit(rng));
    const Quat q0 = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
    {
      const GyrostatFlow flow(I, h, q0, w0);
      for (const double tau : {0.37, -1.3, 6.1}) {
        const GyrostatFlow::State s = flow.state(tau), r = taylor_state(I, h, q0, w0, tau);
        const double ew = (s.omega_b - r.omega_b).norm() / w0.norm(),
                     eR = Eigen::AngleAxisd(s.q * r.q.conjugate()).angle();
        worst[0] = std::max(worst[0], ew), worst[1] = std::max(worst[1], eR);
        EXPECT_LT(ew, 1e-12) << "case " << k << ", tau " << tau << " regime " << int(flow.regime());
        EXPECT_LT(eR, 1e-12) << "case " << k << ", tau " << tau << " regime " << int(flow.regime());
      }
    }
  }
  std::printf("worst relative omega error %.2e, attitude %.2e rad\n", worst[0], worst[1]);
}

TEST(GyrostatFlow, SteadySpinsAndTheSeparatrixHaveTheirOwnRegimes) {
  // h and ω along the same principal axis: Ṁ = 0, a uniform rotation R₀ exp(t[ω]×).
  const Vec3 I(1.0, 2.0, 3.0), w0(0.0, 0.7, 0.0);
  const GyrostatFlow steady(I, Vec3(0.0, 1.5, 0.0), kQ0, w0);
  EXPECT_EQ(steady.regime(), GyrostatFlow::Regime::steady);
  const Quat expected = kQ0 * Quat(Eigen::AngleAxisd(0.7 * 12.0, Vec3::UnitY()));
  EXPECT_LT(Eigen::AngleAxisd(steady.q(12.0) * expected.conjugate()).angle(), 1e-14);
  EXPECT_EQ(steady.omega_b(12.0), w0);
  // The free body's separatrix exactly (binary fractions): I = (2, 3, 6), ω = (3, 4, 1)/8 gives
  // |M|² − 2E I₂ = −2ω₁² + 18ω₃² = 0, a degenerate lattice: the Taylor series, step by step.
  const Vec3 I_sep(2.0, 3.0, 6.0), w_sep(0.375, 0.5, 0.125);
  const GyrostatFlow separatrix(I_sep, Vec3::Zero(), kQ0, w_sep);
  EXPECT_EQ(separatrix.regime(), GyrostatFlow::Regime::series);
  const GyrostatFlow::State s = separatrix.state(5.0), r = taylor_state(I_sep, Vec3::Zero(), kQ0, w_sep, 5.0);
  // Rounding of 200 steps of 0.1 rad in double: ~200 ε |ω| (about 3e-14).
  EXPECT_LT((s.omega_b - r.omega_b).norm(), 1e-13);
  EXPECT_LT(Eigen::AngleAxisd(s.q * r.q.conjugate()).angle(), 1e-13);
}

TEST(GyrostatFlow, TheSplittingsSeriesDriftAgreesWithTheClosedForm) {
  // The splittings' drift for held rotors (integrate/gyrostat_series.hpp) against the closed form, from
  // random states, over steps from 1e-3 s to 3 s: the substeps at their full reach and the order the
  // drift picks for short ones. Measured: worst 1.1e-14 relative in ω, 1.6e-14 rad.
  std::mt19937_64 rng(2612);
  std::uniform_real_distribution<double> moment(0.5, 3.0), unit(-1.0, 1.0);
  double worst[2] = {0, 0};
  for (int k = 0; k < 60; ++k) {
    const Vec3 I(moment(rng), moment(rng), moment(rng)), h = 2.0 * Vec3(unit(rng), unit(rng), unit(rng));
    const Vec3 w0(unit(rng), unit(rng), unit(rng));
    const Quat q0 = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
    const GyrostatFlow flow(I, h, q0, w0);
    for (const double tau : {1e-3, 0.05, 0.4, 3.0}) {
      const detail::FlowState<double> s =
          gyrostat::series_flow<double, double>(I, h, q0, w0, tau, gyrostat::series_rate<double>(w0, h, I));
      const GyrostatFlow::State r = flow.state(tau);
      const double ew = (s.omega_b - r.omega_b).norm() / w0.norm(),
                   eR = Eigen::AngleAxisd(s.q * r.q.conjugate()).angle();
      worst[0] = std::max(worst[0], ew), worst[1] = std::max(worst[1], eR);
      EXPECT_LT(ew, 1e-13) << "case " << k << ", tau " << tau;
      EXPECT_LT(eR, 1e-13) << "case " << k << ", tau " << tau;
    }
  }
  std::printf("series drift: worst relative omega error %.2e, attitude %.2e rad\n", worst[0], worst[1]);
}

}  // namespace
}  // namespace tumble
