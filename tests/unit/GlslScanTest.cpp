// gl::declaresBufferBlock (src/gpu/GlslScan.h): the storage-block scan of ProgramChecks' portable audit,
// which counts a block in every stage whose source declares it when Mesa reports no referencing stage.
#include "gpu/GlslScan.h"

#include <gtest/gtest.h>

using bounce::gl::declaresBufferBlock;

TEST(GlslScan, BufferBlockIsFoundAsAWholeWordAfterTheKeyword) {
    const char* text = "layout(std430, binding = 3) readonly buffer Elements {\n  vec4 e[];\n};\n"
                       "layout(std430, binding = 4) buffer\n\tCounts{ uint n; };\n";
    EXPECT_TRUE(declaresBufferBlock(text, "Elements"));
    EXPECT_TRUE(declaresBufferBlock(text, "Counts"));  // a newline and a tab between, no space before '{'
    EXPECT_FALSE(declaresBufferBlock(text, "Element"));  // a prefix of a declared name
    EXPECT_FALSE(declaresBufferBlock(text, "lements"));
    EXPECT_FALSE(declaresBufferBlock(text, "e"));
    EXPECT_FALSE(declaresBufferBlock(text, ""));
}

TEST(GlslScan, OtherWordsEndingOrStartingWithBufferAreNotTheKeyword) {
    EXPECT_FALSE(declaresBufferBlock("uniform samplerBuffer Lights;", "Lights"));
    EXPECT_FALSE(declaresBufferBlock("uint bufferLights = 0u;", "Lights"));
    EXPECT_FALSE(declaresBufferBlock("int buffer_ Lights;", "Lights"));
    EXPECT_FALSE(declaresBufferBlock("bufferLights", "Lights"));  // no white space after the keyword
    EXPECT_TRUE(declaresBufferBlock("xbuffer A; buffer A {", "A"));  // a later occurrence counts
    EXPECT_TRUE(declaresBufferBlock("buffer A", "A"));              // the name at the end of the text
}
