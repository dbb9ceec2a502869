/* Inputs and outputs of test/kernels/bsdf_test.cl, shared with the host tests in test/bsdf/, so that the
 * host and the device run the very same function on the same bytes. */
#ifndef COHORT_BSDF_TEST_IO_H
#define COHORT_BSDF_TEST_IO_H

#include "common/shading/bsdf.h"
#include "common/shading/sheen.h"

typedef struct BsdfTestIn {
  Bsdf bsdf;
  co_vec3 wi;        /* local frame */
  float u_lobe, u1, u2;
  co_vec3 wo_query;  /* a direction where eval and pdf are also evaluated */
} BsdfTestIn;
CO_STATIC_ASSERT(sizeof(BsdfTestIn) == 68, "BsdfTestIn layout");

typedef struct BsdfTestOut {
  BsdfSample sample;
  co_vec3 eval_sample; /* bsdf_eval(wi, sample.wo) */
  float pdf_sample;    /* bsdf_pdf(wi, sample.wo) */
  co_vec3 eval_query;  /* bsdf_eval(wi, wo_query) */
  float pdf_query;     /* bsdf_pdf(wi, wo_query) */
} BsdfTestOut;
CO_STATIC_ASSERT(sizeof(BsdfTestOut) == 68, "BsdfTestOut layout");

CO_INLINE BsdfTestOut bsdf_test_run(const BsdfTestIn* q) {
  BsdfTestOut r;
  r.sample = bsdf_sample(&q->bsdf, q->wi, q->u_lobe, q->u1, q->u2);
  r.eval_sample = bsdf_eval(&q->bsdf, q->wi, r.sample.wo);
  r.pdf_sample = bsdf_pdf(&q->bsdf, q->wi, r.sample.wo);
  r.eval_query = bsdf_eval(&q->bsdf, q->wi, q->wo_query);
  r.pdf_query = bsdf_pdf(&q->bsdf, q->wi, q->wo_query);
  return r;
}

#endif
